// SPDX-License-Identifier: BSD-3-Clause
/**
 * The Schlieren plugin's GUI side (client only; the trace runs where the data is).
 *
 * pqSchlierenToolbar: a toolbar with "Follow camera" (a toggle of the active SchlierenImage's
 * FollowCamera property), "Stop refinement" and "Show in a schlieren view". It owns one
 * pqSchlierenFollower per SchlierenImage of the session.
 *
 * pqSchlierenFollower: when a SchlierenImage is first shown in a 3D render view (Apply), opens its
 * film in a 2D render view in a split beside it (intensity in a grey 0-1 map, rgb as direct
 * colours for the colour filter, 2D interaction, the camera fitted to the film and refitted on
 * resize), and hides it from the 3D view. With FollowCamera on, a change of the 3D view's camera
 * sets ViewDirection/ViewUp from it and traces InteractivePasses passes; once the camera has
 * rested, passes are added in chunks sized to a fraction of a second up to the target (the Passes
 * the user set) from a Qt timer, so that the event loop runs between chunks: a new drag or Stop
 * interrupts the refinement within one chunk, and the image keeps the passes done. The filter
 * traces only the passes it does not have yet, so the converged image equals a trace of all the
 * passes at once.
 */
#ifndef pqSchlierenToolbar_h
#define pqSchlierenToolbar_h

#include <QElapsedTimer>
#include <QMap>
#include <QObject>
#include <QPointer>
#include <QTimer>
#include <QToolBar>

#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "vtkObject.h"
#include "vtkWeakPointer.h"

#include "pqDataRepresentation.h"

class QAction;

class pqSchlierenFollower : public QObject
{
  Q_OBJECT
public:
  pqSchlierenFollower(pqPipelineSource* image, QObject* parent);
  ~pqSchlierenFollower() override;

  pqPipelineSource* image() const { return this->Image; }
  pqRenderView* imageView() const { return this->ImageView; }
  bool following() const;
  /// A refinement is under way or about to start (Stop Refinement acts on it).
  bool refining() const;
  /// Sets FollowCamera (the property, so that the panel and pvpython see it).
  void setFollowing(bool on);
  /// Opens (or re-opens) the image's 2D view beside `view3D` (or the view it was shown in).
  void openImageView(pqRenderView* view3D);
  /// Stops the refinement in progress; the image keeps the passes done.
  void stop();
  /// The filter goes: its image view (if it shows nothing else) goes too.
  void closeImageView();
  /// SCHLIEREN_GUI_TRACE=1: one line on stderr per event (for tests and timing).
  void log(const char* event) const;

Q_SIGNALS:
  void stateChanged();

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private Q_SLOTS:
  void onRepresentationAdded(pqPipelineSource*, pqDataRepresentation*, int);
  void onCameraModified();
  void onFollowModified();
  void onResolutionModified();
  void onPropertyModified(vtkObject* property);
  void retrace();
  void refineStep();
  void fitImageView();
  void onTimeChanged();

private:
  void watchCamera(pqRenderView* view);
  void openWhenIdle(QPointer<pqDataRepresentation> added, int tries);
  /// After an Apply: the first opens the image's view (or shows it in the 3D view); a later one
  /// opens the view a failed first trace did not, if the image is there now.
  void onApplied();
  void openAfterApply(int tries);
  void setPasses(int passes);
  /// A new image by the one rule: InteractivePasses first, then chunks up to Passes
  /// (keepPasses: from the passes the image shown has, for a larger Passes alone).
  void startImage(const char* why, bool keepPasses);
  /// The image view colours rgb as colours where the image has them, intensity in grey otherwise.
  void applyColouring();
  void restoreResolution();
  int passes() const;
  int askedPasses() const;
  void update(const char* what);
  /// Following the camera, or reaching an applied Passes in chunks.
  bool refinable() const { return this->following() || this->Progressive; }

  QPointer<pqPipelineSource> Image;
  QPointer<pqRenderView> View3D;
  QPointer<pqRenderView> ImageView;
  QPointer<pqRenderView> PendingView; // the 3D view of an Apply that has not shown the image yet
  bool FirstApply = false;   // made in the GUI, not applied yet
  bool PendingFirst = false; // PendingView is the first Apply's
  vtkWeakPointer<vtkObject> Camera;
  unsigned long CameraTag = 0;
  int Target = 1;        // the passes the user asked for
  bool Guard = false;    // set while this object changes PassLimit or Resolution itself
  bool Stopped = false;  // Stop pressed: no refinement until the next camera change
  bool RetracePending = false;
  bool Progressive = false; // an applied trace (Follow Camera off) is reached in chunks
  bool Busy = false; // inside our own pipeline update
  bool NewImage = false; // a property other than Passes changed in this event
  double SecondsPerPass = 0; // measured on the last update
  int LastPasses = 0;        // the passes of the image shown
  int LastChunk = 1;         // passes added by the last refinement chunk
  int FullResolution[2] = { 512, 512 }; // the film the user asked for
  bool Coarse = false;       // the film is InteractiveScale of it (the view is turning)
  double FilmBounds[4] = { 0, 0, 0, 0 };
  QElapsedTimer Loading; // valid from a Load State until its image view is on the screen
  QTimer RestTimer;   // the camera rested: start refining
  QTimer RefineTimer; // one chunk of passes per tick
};

class pqSchlierenToolbar : public QToolBar
{
  Q_OBJECT
public:
  pqSchlierenToolbar(QWidget* parent = nullptr);
  ~pqSchlierenToolbar() override;

private Q_SLOTS:
  void onSourceAdded(pqPipelineSource*);
  void onSourceRemoved(pqPipelineSource*);
  void updateActions();
  void toggleFollow(bool);
  void stopRefinement();
  void showImageView();

private:
  pqSchlierenFollower* active() const;

  QMap<pqPipelineSource*, QPointer<pqSchlierenFollower>> Followers;
  QAction* FollowAction;
  QAction* StopAction;
  QAction* ViewAction;
};

#endif
