// SPDX-License-Identifier: BSD-3-Clause
/**
 * What the GUI says about the plugin's filters (client only).
 *
 * - The Output Messages show each error of the plugin's filters once: the pipeline's own
 *   "Algorithm vtkSchlierenImage (...) returned failure for request: ..." line that follows every
 *   failed request of one of them repeats, in VTK's words, what the filter has just said, and is
 *   suppressed (the other filters' lines are left as ParaView shows them).
 * - A greyed menu entry of SchlierenImage or RefractionOctree (their input must be an image) says
 *   in its status tip what to do: apply RefractiveIndex first, which resamples any grid onto an
 *   image and computes n - 1 (ParaView's own tip says only "Input must be vtkImageData").
 * - Model Automatic's choice (RefractiveIndex's note: the model, the gas, the units) opens the
 *   Output Messages, once per new choice: ParaView opens them by itself only for warnings and
 *   errors, and a wrong choice makes a wrong image.
 * - SCHLIEREN_GUI_TRACE=1: every message the Output Messages show is also written to stderr as
 *   one line "schlieren-gui <seconds> message <type> <text, percent-encoded>", for the GUI tests.
 */
#ifndef pqSchlierenMessages_h
#define pqSchlierenMessages_h

#include <QObject>
#include <QString>

class QAction;

class pqSchlierenMessages : public QObject
{
  Q_OBJECT
public:
  pqSchlierenMessages(QObject* parent);

private:
  /// Finds the Output Messages widget (it may come after the plugin) and hooks it once.
  void hookOutput(int tries);
  /// Gives the image filters' menu entries their hint (again after ParaView resets the tip).
  void hintActions();
  void hint(QAction* action);

  bool OutputHooked = false;
  QString LastChoice; // the last Model Automatic note the Output Messages were opened for
};

#endif
