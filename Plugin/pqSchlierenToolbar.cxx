// SPDX-License-Identifier: BSD-3-Clause
#include "pqSchlierenToolbar.h"
#include "pqSchlierenMessages.h"
#ifdef SCHLIEREN_OWN_HELP
#include "SchlierenHelp.h"
#endif

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqDataRepresentation.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqProgressManager.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqTimeKeeper.h"
#include "pqUndoStack.h"
#include "pqRepresentation.h"
#include "pqView.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMPropertyIterator.h"
#include "vtkSetGet.h"
#include "vtkSmartPointer.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionProxy.h"
#include "vtkSMViewLayoutProxy.h"
#include "vtkSMViewProxy.h"

#include <QAction>
#include <QDateTime>
#include <QElapsedTimer>
#include <QEvent>
#include <QIcon>
#include <QLineEdit>
#include <QMainWindow>
#include <QStatusBar>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{
// The refinement adds passes in chunks of about this many seconds: the event loop (a new drag,
// Stop) runs between chunks.
constexpr double ChunkSeconds = 0.25;
// The camera counts as resting after this long without a change.
constexpr int RestMilliseconds = 300;
// ViewDirection/ViewUp differences below this are not a rotation (a zoom or a pan).
constexpr double SameDirection = 1e-9;

// The GUI's own InteractivePasses and InteractiveScale (no command: the filter never sees them,
// so nothing refuses them there): a value outside the XML domain is said once in the Output
// Messages with the range, rather than changed in silence; the passes then use the nearest end.
int InteractivePassesOf(vtkSMProxy* proxy)
{
  static int said = 1; // the last value warned about (1: none)
  if (!proxy->GetProperty("InteractivePasses"))
  {
    return 1; // NumericalSchlieren: no passes
  }
  const int passes = vtkSMPropertyHelper(proxy, "InteractivePasses").GetAsInt();
  const int used = std::min(256, std::max(1, passes));
  if (used != passes && passes != said)
  {
    vtkGenericWarningMacro("InteractivePasses is " << passes << ": it must be in [1, 256]; the "
                           "toolbar uses " << used << " while the view turns.");
  }
  said = used != passes ? passes : 1;
  return used;
}

double InteractiveScaleOf(vtkSMProxy* proxy)
{
  static double said = 1; // the last value warned about (1: none)
  if (!proxy->GetProperty("InteractiveScale"))
  {
    return 1; // NumericalSchlieren: the full film
  }
  const double scale = vtkSMPropertyHelper(proxy, "InteractiveScale").GetAsDouble();
  const bool outside = !(scale >= 0.1 && scale <= 1);
  if (outside && scale != said)
  {
    vtkGenericWarningMacro("InteractiveScale is " << scale << ": it must be in [0.1, 1]; "
                           << (scale > 0 && scale < 1 ? "the film is coarsened by it anyway"
                                                      : "the film is not coarsened")
                           << " while the view turns.");
  }
  said = outside ? scale : 1;
  return scale;
}

bool IsSchlierenImage(pqPipelineSource* source)
{
  // SchlierenImage, and NumericalSchlieren shown and following the camera as it is
  const QString name = source && source->getProxy() ? source->getProxy()->GetXMLName() : "";
  return name == QLatin1String("SchlierenImage") || name == QLatin1String("NumericalSchlieren");
}

// ParaView processes events while a pipeline update reports progress: nothing here starts work
// inside another update (it waits for the update to end)
int UpdatesInProgress = 0;
bool Idle()
{
  return UpdatesInProgress == 0;
}

// The image view's colouring: rgb as the colours themselves (MapScalars off), or intensity
// through a grey map over [0, 1]. The member SetScalarColoring (the static form is gone from
// ParaView 5.12 on).
void SetColouring(vtkSMProxy* repr, bool colour)
{
  auto* pv = vtkSMPVRepresentationProxy::SafeDownCast(repr);
  if (!pv)
  {
    return;
  }
  if (colour)
  {
    pv->SetScalarColoring("rgb", vtkDataObject::POINT);
    vtkSMPropertyHelper(repr, "MapScalars", true).Set(0); // rgb in [0, 1] as colours
  }
  else
  {
    pv->SetScalarColoring("intensity", vtkDataObject::POINT);
    vtkSMPropertyHelper(repr, "MapScalars", true).Set(1);
    if (vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy())
    {
      vtkSMTransferFunctionProxy::ApplyPreset(lut, "Grayscale", false);
      vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode", true).Set(-1); // Never
      vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, 0.0, 1.0, false);
      lut->UpdateVTKObjects();
    }
  }
  repr->UpdateVTKObjects();
}

// SchlierenPhotograph, wherever it is shown (its representations' hints make output 0 a slice,
// output 1 a surface): the overlay coloured by its active scalars (the array Overlay names; a grey
// map, a diverging one for the difference) and the lines by line_distance, after every update (a
// new Overlay is a new active array). A user gets the overlay without setting the colouring.
void ColourPhotograph(pqDataRepresentation* repr)
{
  auto* pv = repr ? vtkSMPVRepresentationProxy::SafeDownCast(repr->getProxy()) : nullptr;
  pqOutputPort* port = repr ? repr->getOutputPortFromInput() : nullptr;
  vtkSMViewProxy* view = repr && repr->getView() ? repr->getView()->getViewProxy() : nullptr;
  if (!pv || !port)
  {
    return;
  }
  vtkPVDataInformation* info = port->getDataInformation();
  if (!info || info->GetNumberOfPoints() == 0)
  {
    return; // refused: nothing shown
  }
  const bool lines = port->getPortNumber() == 1;
  vtkPVArrayInformation* active = lines
    ? info->GetCellDataInformation()->GetArrayInformation("line_distance")
    : info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);
  if (!active || !active->GetName())
  {
    return;
  }
  const std::string name = active->GetName();
  const char* now = vtkSMPropertyHelper(pv, "ColorArrayName", true).GetInputArrayNameToProcess();
  if (view && now && name != now)
  {
    pv->SetScalarBarVisibility(view, false); // the legend of the array shown before
  }
  pv->SetScalarColoring(name.c_str(), lines ? vtkDataObject::CELL : vtkDataObject::POINT);
  double range[2];
  active->GetComponentRange(0, range);
  if (vtkSMProxy* lut = vtkSMPropertyHelper(pv, "LookupTable", true).GetAsProxy())
  {
    if (!lines)
    {
      vtkSMTransferFunctionProxy::ApplyPreset(lut, name == "difference" ? "Cool to Warm" : "Grayscale", false);
    }
    else
    {
      // the photograph's lines (no distance: NaN) half transparent, so that the film's lines
      // under them show their distance's colour
      vtkSMPropertyHelper(lut, "NanOpacity", true).Set(0.4);
    }
    if (name == "difference") // 0 (agreement) in the middle of the diverging map
    {
      const double m = std::max(std::fabs(range[0]), std::fabs(range[1]));
      range[0] = -m;
      range[1] = m;
    }
    vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode", true).Set(-1); // Never: set here
    if (range[1] > range[0])
    {
      vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, range[0], range[1], false);
    }
    lut->UpdateVTKObjects();
  }
  if (view)
  {
    pv->SetScalarBarVisibility(view, true);
  }
  pv->UpdateVTKObjects();
}

void StatusMessage(const QString& text)
{
  if (auto* window = qobject_cast<QMainWindow*>(pqCoreUtilities::mainWidget()))
  {
    window->statusBar()->showMessage(text, 5000);
  }
}
}

//------------------------------------------------------------------------------
pqSchlierenFollower::pqSchlierenFollower(pqPipelineSource* image, QObject* parent)
  : QObject(parent)
  , Image(image)
{
  this->Target = std::max(1, this->askedPasses());
  QObject::connect(image,
    SIGNAL(representationAdded(pqPipelineSource*, pqDataRepresentation*, int)), this,
    SLOT(onRepresentationAdded(pqPipelineSource*, pqDataRepresentation*, int)));
  // an update made elsewhere (Apply, a script): the image shown has the passes asked for
  QObject::connect(image, QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated), this,
    [this](pqPipelineSource*) {
    if (!this->Busy)
    {
      this->LastPasses = this->passes();
      this->log("updated"); // an update made elsewhere (Apply, Load State, a script)
      if (this->Progressive && !this->Stopped && this->LastPasses < this->Target)
      {
        this->RestTimer.start(0); // the rest of the image, in chunks
      }
    }
    this->applyColouring();
  });
  QObject::connect(image, &pqProxy::modifiedStateChanged, this, [this]() {
    // made in the GUI (the pipeline browser's "uninitialised" state until its first Apply)
    if (this->Image && this->Image->modifiedState() == pqProxy::UNINITIALIZED)
    {
      this->FirstApply = true;
    }
    this->onApplied();
  });
  vtkSMProxy* proxy = image->getProxy();
  pqCoreUtilities::connect(proxy->GetProperty("FollowCamera"), vtkCommand::ModifiedEvent, this,
    SLOT(onFollowModified()));
  pqCoreUtilities::connect(proxy->GetProperty("Resolution"), vtkCommand::ModifiedEvent, this,
    SLOT(onResolutionModified()));
  vtkSmartPointer<vtkSMPropertyIterator> it;
  it.TakeReference(proxy->NewPropertyIterator());
  for (it->Begin(); !it->IsAtEnd(); it->Next())
  {
    pqCoreUtilities::connect(
      it->GetProperty(), vtkCommand::ModifiedEvent, this, SLOT(onPropertyModified(vtkObject*)));
  }
  vtkSMPropertyHelper(proxy, "Resolution").Get(this->FullResolution, 2);
  this->RestTimer.setSingleShot(true);
  QObject::connect(&this->RestTimer, &QTimer::timeout, this, [this]() {
    if (this->following() && !this->Stopped && this->Coarse)
    {
      this->restoreResolution(); // the refinement is on the full film
    }
    if (this->refinable() && !this->Stopped && this->LastPasses < this->Target)
    {
      this->RefineTimer.start();
      Q_EMIT this->stateChanged();
    }
  });
  this->RefineTimer.setInterval(1);
  QObject::connect(&this->RefineTimer, SIGNAL(timeout()), this, SLOT(refineStep()));
  if (pqTimeKeeper* keeper = image->getServer() ? image->getServer()->getTimeKeeper() : nullptr)
  {
    QObject::connect(keeper, &pqTimeKeeper::timeChanged, this, &pqSchlierenFollower::onTimeChanged);
  }
  if (pqApplicationCore::instance()->isLoadingState())
  {
    // File > Load State: the image of the state (its Passes, the passes it had when it was
    // saved) is reached in chunks like any other, its first pass traced when the views show
    this->startImage("loading", false);
    proxy->UpdateVTKObjects();
    this->Loading.start();
  }
}

//------------------------------------------------------------------------------
pqSchlierenFollower::~pqSchlierenFollower()
{
  if (this->Camera)
  {
    this->Camera->RemoveObserver(this->CameraTag);
  }
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::closeImageView()
{
  // the image view shows this image alone: it goes with it, and its cell of the layout too
  QPointer<pqRenderView> view = this->ImageView;
  this->ImageView = nullptr;
  if (!view)
  {
    return;
  }
  QPointer<pqRenderView> view3D = this->View3D;
  QTimer::singleShot(0, [view, view3D]() {
    if (!view)
    {
      return;
    }
    for (pqRepresentation* repr : view->getRepresentations())
    {
      if (repr && repr->isVisible())
      {
        return; // the user showed something else there: the view stays
      }
    }
    vtkSMViewProxy* viewProxy = vtkSMViewProxy::SafeDownCast(view->getViewProxy());
    if (vtkSMViewLayoutProxy* layout = vtkSMViewLayoutProxy::FindLayout(viewProxy))
    {
      const int location = layout->RemoveView(viewProxy);
      if (location >= 0)
      {
        layout->Collapse(location);
      }
    }
    pqApplicationCore::instance()->getObjectBuilder()->destroy(view);
    if (view3D && !pqActiveObjects::instance().activeView())
    {
      // the 3D view the image was made from is active again (no view active greys the camera
      // toolbar and the view's controls)
      pqActiveObjects::instance().setActiveView(view3D);
    }
  });
}

//------------------------------------------------------------------------------
bool pqSchlierenFollower::following() const
{
  return this->Image && vtkSMPropertyHelper(this->Image->getProxy(), "FollowCamera").GetAsInt() != 0;
}

//------------------------------------------------------------------------------
int pqSchlierenFollower::askedPasses() const
{
  // NumericalSchlieren has no passes: one update is the image
  return !this->Image ? 0
                      : this->Image->getProxy()->GetProperty("Passes")
      ? vtkSMPropertyHelper(this->Image->getProxy(), "Passes").GetAsInt()
      : 1;
}

//------------------------------------------------------------------------------
int pqSchlierenFollower::passes() const
{
  // the passes the filter traces: Passes, at most PassLimit where that is set
  const int asked = this->askedPasses();
  const int limit =
    this->Image ? vtkSMPropertyHelper(this->Image->getProxy(), "PassLimit", true).GetAsInt() : 0;
  return limit > 0 ? std::min(asked, limit) : asked;
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::setPasses(int passes)
{
  // the refinement's steps go to PassLimit: the Passes field keeps the user's target
  // (0: no limit)
  if (!this->Image->getProxy()->GetProperty("PassLimit") ||
    vtkSMPropertyHelper(this->Image->getProxy(), "PassLimit").GetAsInt() == passes)
  {
    return;
  }
  // the GUI's own bookkeeping, never an entry of the undo stack: undone, a PassLimit of an Apply
  // would lift the limit of the image the Undo starts
  SCOPED_UNDO_EXCLUDE();
  this->Guard = true;
  vtkSMPropertyHelper(this->Image->getProxy(), "PassLimit").Set(passes);
  this->Image->getProxy()->UpdateProperty("PassLimit");
  this->Guard = false;
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::log(const char* event) const
{
  // SCHLIEREN_GUI_TRACE=1: one line per event on stderr (wall-clock seconds, as Python's
  // time.time()), for tests and for timing the loop
  static const bool enabled = std::getenv("SCHLIEREN_GUI_TRACE") != nullptr;
  if (!enabled || !this->Image)
  {
    return;
  }
  vtkSMProxy* p = this->Image->getProxy();
  double d[3], u[3];
  vtkSMPropertyHelper(p, "ViewDirection").Get(d, 3);
  vtkSMPropertyHelper(p, "ViewUp").Get(u, 3);
  int r[2];
  vtkSMPropertyHelper(p, "Resolution").Get(r, 2);
  // what the Properties panel's Passes field shows (its widget is named after the property)
  QString field = "-";
  QPoint at(-1, -1);
  if (QWidget* main = pqCoreUtilities::mainWidget())
  {
    for (QWidget* w : main->findChildren<QWidget*>("Passes"))
    {
      if (auto* edit = w->findChild<QLineEdit*>())
      {
        field = edit->text().isEmpty() ? "-" : edit->text();
        if (edit->isVisible())
        {
          at = edit->mapToGlobal(edit->rect().center());
        }
        break;
      }
    }
  }
  std::fprintf(stderr,
    "schlieren-gui %.6f %s %s passes=%d target=%d resolution=%dx%d seconds_per_pass=%.4f "
    "dir=%.17g,%.17g,%.17g up=%.17g,%.17g,%.17g passes_property=%d passes_field=%s field_at=%d,%d "
    "view_shown=%d\n",
    QDateTime::currentMSecsSinceEpoch() / 1000.0, event,
    this->Image->getSMName().toLocal8Bit().constData(), this->passes(), this->Target, r[0], r[1],
    this->SecondsPerPass, d[0], d[1], d[2], u[0], u[1], u[2], this->askedPasses(),
    field.toLocal8Bit().constData(), at.x(), at.y(),
    this->ImageView && this->ImageView->widget() && this->ImageView->widget()->isVisible() ? 1 : 0);
  std::fflush(stderr);
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::setFollowing(bool on)
{
  if (!this->Image || on == this->following())
  {
    return;
  }
  vtkSMPropertyHelper(this->Image->getProxy(), "FollowCamera").Set(on ? 1 : 0);
  this->Image->getProxy()->UpdateVTKObjects();
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onRepresentationAdded(pqPipelineSource*, pqDataRepresentation* repr, int)
{
  // the representation joins its view after this signal: look once the Apply (or Show) is done
  QPointer<pqDataRepresentation> added(repr);
  this->openWhenIdle(added, 200);
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::openWhenIdle(QPointer<pqDataRepresentation> added, int tries)
{
  QTimer::singleShot(tries == 200 ? 0 : 50, this, [this, added, tries]() {
    if (!Idle() || this->Busy)
    {
      if (tries > 0)
      {
        this->openWhenIdle(added, tries - 1);
      }
      return;
    }
    auto* view = added ? qobject_cast<pqRenderView*>(added->getView()) : nullptr;
    if (!view || view == this->ImageView || !this->Image)
    {
      return;
    }
    // a loaded state (or a script) brings its own views: the image shown in a 2D view is the image
    // view, a view where it is hidden the 3D view; only an image newly shown in a 3D view (Apply)
    // opens a view of its own
    vtkSMProxy* viewProxy = view->getViewProxy();
    const bool twoD = vtkSMPropertyHelper(viewProxy, "InteractionMode", true).GetAsInt() == 1;
    const bool visible = added->isVisible();
    if (twoD && visible)
    {
      if (!this->ImageView)
      {
        this->ImageView = view;
        this->ImageView->widget()->installEventFilter(this);
        this->fitImageView();
        this->log("adopted");
      }
      return;
    }
    if (!this->View3D)
    {
      this->View3D = view;
      this->watchCamera(view);
    }
    if (!visible)
    {
      return;
    }
    if (!this->ImageView &&
      vtkSMPropertyHelper(this->Image->getProxy(), "OpenImageView").GetAsInt() != 0)
    {
      vtkPVDataInformation* info = this->Image->getOutputPort(0)->getDataInformation();
      if (!info || info->GetNumberOfPoints() == 0)
      {
        // the trace failed (its error is in the Output Messages): no empty view; the image is
        // hidden in the 3D view and the view opens after the next Apply that makes an image
        vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
        controller->Hide(vtkSMSourceProxy::SafeDownCast(this->Image->getProxy()), 0,
          vtkSMViewProxy::SafeDownCast(view->getViewProxy()));
        view->render();
        this->PendingView = view;
        this->log("not-opened");
        return;
      }
      this->openImageView(view);
    }
  });
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onApplied()
{
  if (!this->Image || this->Image->modifiedState() != pqProxy::UNMODIFIED)
  {
    return;
  }
  if (this->FirstApply)
  {
    // The image's first Apply. Its <View type="None"/> hint keeps ParaView from showing it in the
    // 3D view, where the film would be drawn in colour with a legend until its own view opened:
    // it is shown here instead, in its own 2D view beside the 3D view that was active (or in that
    // view itself with OpenImageView off). A failed trace shows nothing until an Apply succeeds.
    this->FirstApply = false;
    this->PendingView = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
    this->PendingFirst = true;
  }
  if (!this->PendingView || this->ImageView)
  {
    return;
  }
  this->openAfterApply(200);
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::openAfterApply(int tries)
{
  QTimer::singleShot(tries == 200 ? 0 : 50, this, [this, tries]() {
    if (!this->PendingView || this->ImageView || !this->Image)
    {
      return;
    }
    if (!Idle() || this->Busy)
    {
      if (tries > 0)
      {
        this->openAfterApply(tries - 1);
      }
      return;
    }
    QPointer<pqRenderView> view = this->PendingView;
    const bool first = this->PendingFirst;
    this->PendingFirst = false;
    if (first && !this->Image->getRepresentations(nullptr).empty())
    {
      this->PendingView = nullptr; // a script showed it already: its views are the user's
      return;
    }
    if (!this->View3D)
    {
      this->View3D = view;
      this->watchCamera(view);
    }
    vtkSMSourceProxy* source = vtkSMSourceProxy::SafeDownCast(this->Image->getProxy());
    if (vtkSMPropertyHelper(source, "OpenImageView").GetAsInt() == 0)
    {
      // the user's choice: the film in the 3D view, as ParaView shows any output
      this->PendingView = nullptr;
      vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
      controller->Show(source, 0, vtkSMViewProxy::SafeDownCast(view->getViewProxy()));
      view->render();
      return;
    }
    source->UpdatePipeline();
    vtkPVDataInformation* info = this->Image->getOutputPort(0)->getDataInformation();
    if (info && info->GetNumberOfPoints() > 0)
    {
      this->PendingView = nullptr;
      this->openImageView(view);
    }
    else if (first)
    {
      // the trace failed (its error is in the Output Messages): no empty view; it opens after
      // the next Apply that makes an image
      this->log("not-opened");
    }
  });
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::watchCamera(pqRenderView* view)
{
  if (this->Camera)
  {
    this->Camera->RemoveObserver(this->CameraTag);
    this->Camera = nullptr;
  }
  if (!view || !view->getRenderViewProxy())
  {
    return;
  }
  this->Camera = view->getRenderViewProxy()->GetActiveCamera();
  this->CameraTag = pqCoreUtilities::connect(
    this->Camera, vtkCommand::ModifiedEvent, this, SLOT(onCameraModified()));
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::openImageView(pqRenderView* view3D)
{
  if (!this->Image)
  {
    return;
  }
  if (!view3D)
  {
    view3D = this->View3D;
  }
  if (this->ImageView)
  {
    pqActiveObjects::instance().setActiveView(this->ImageView);
    return;
  }
  vtkSMSourceProxy* source = vtkSMSourceProxy::SafeDownCast(this->Image->getProxy());
  pqObjectBuilder* builder = pqApplicationCore::instance()->getObjectBuilder();

  // a split beside the 3D view, in its layout
  vtkSMViewLayoutProxy* layout =
    view3D ? vtkSMViewLayoutProxy::FindLayout(view3D->getViewProxy()) : nullptr;
  if (!layout)
  {
    layout = pqActiveObjects::instance().activeLayout();
  }
  int cell = -1;
  if (layout && view3D)
  {
    const int location = layout->GetViewLocation(view3D->getViewProxy());
    if (location >= 0)
    {
      const int first = layout->SplitHorizontal(location, 0.5);
      cell = first >= 0 ? first + 1 : -1;
    }
  }
  pqView* view = builder->createView("RenderView", this->Image->getServer());
  this->ImageView = qobject_cast<pqRenderView*>(view);
  if (!this->ImageView)
  {
    return;
  }
  vtkSMProxy* viewProxy = this->ImageView->getViewProxy();
  if (layout)
  {
    if (cell < 0 || !layout->AssignView(cell, vtkSMViewProxy::SafeDownCast(viewProxy)))
    {
      layout->AssignViewToAnyCell(vtkSMViewProxy::SafeDownCast(viewProxy), 0);
    }
  }
  vtkSMPropertyHelper(viewProxy, "InteractionMode").Set(1); // 2D
  vtkSMPropertyHelper(viewProxy, "OrientationAxesVisibility").Set(0);
  vtkSMPropertyHelper(viewProxy, "CameraParallelProjection").Set(1);
  viewProxy->UpdateVTKObjects();

  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMProxy* repr = controller->Show(source, 0, vtkSMViewProxy::SafeDownCast(viewProxy));
  if (repr)
  {
    // ColorFilter, or a band of wavelengths: the rgb colours (until the image says)
    const bool colour = vtkSMPropertyHelper(source, "Cutoff", true).GetAsInt() == 4 ||
      vtkSMPropertyHelper(source, "WavelengthRange", true).GetAsDouble(1) > 0;
    SetColouring(repr, colour);
  }
  if (view3D)
  {
    controller->Hide(source, 0, vtkSMViewProxy::SafeDownCast(view3D->getViewProxy()));
    if (!this->View3D)
    {
      this->View3D = view3D;
      this->watchCamera(view3D);
    }
  }
  this->ImageView->widget()->installEventFilter(this);
  this->applyColouring();
  this->fitImageView();
  this->ImageView->render();
  if (view3D)
  {
    view3D->render();
    pqActiveObjects::instance().setActiveView(view3D); // the user goes on turning the volume
  }
  pqActiveObjects::instance().setActiveSource(this->Image);
  this->log("opened");
}

//------------------------------------------------------------------------------
bool pqSchlierenFollower::eventFilter(QObject* watched, QEvent* event)
{
  if (this->ImageView && watched == this->ImageView->widget() && event->type() == QEvent::Resize)
  {
    QTimer::singleShot(0, this, SLOT(fitImageView()));
  }
  return QObject::eventFilter(watched, event);
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::fitImageView()
{
  if (!this->ImageView || !this->Image)
  {
    return;
  }
  vtkPVDataInformation* info = this->Image->getOutputPort(0)->getDataInformation();
  double* b = info ? info->GetBounds() : nullptr;
  if (!b || !(b[0] <= b[1]) || !(b[2] <= b[3]))
  {
    return;
  }
  const QSize size = this->ImageView->widget()->size();
  const double aspect =
    size.height() > 0 ? double(std::max(1, size.width())) / size.height() : 1.0;
  const double cx = 0.5 * (b[0] + b[1]), cy = 0.5 * (b[2] + b[3]);
  const double hx = 0.5 * (b[1] - b[0]), hy = 0.5 * (b[3] - b[2]);
  // the whole film inside the view, its aspect kept: fit the tighter of the two directions
  const double scale = 1.02 * std::max(hy, hx / aspect);
  if (!(scale > 0))
  {
    return;
  }
  vtkSMProxy* viewProxy = this->ImageView->getViewProxy();
  const double focal[3] = { cx, cy, 0.0 };
  const double position[3] = { cx, cy, 10.0 * std::max(hx, hy) + 1.0 };
  const double up[3] = { 0.0, 1.0, 0.0 };
  vtkSMPropertyHelper(viewProxy, "CameraFocalPoint").Set(focal, 3);
  vtkSMPropertyHelper(viewProxy, "CameraPosition").Set(position, 3);
  vtkSMPropertyHelper(viewProxy, "CameraViewUp").Set(up, 3);
  vtkSMPropertyHelper(viewProxy, "CameraParallelScale").Set(scale);
  viewProxy->UpdateVTKObjects();
  std::copy(b, b + 4, this->FilmBounds);
  this->ImageView->render();
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::applyColouring()
{
  // the image view colours what the image holds: rgb (a colour filter, a band of wavelengths) as
  // colours, intensity in grey otherwise, switched when a change of the settings changes it; an
  // array the user picked (neither of the two) is left alone
  if (!this->ImageView || !this->Image)
  {
    return;
  }
  pqDataRepresentation* repr = this->Image->getRepresentation(this->ImageView);
  vtkPVDataInformation* info = this->Image->getOutputPort(0)->getDataInformation();
  if (!repr || !info || info->GetNumberOfPoints() == 0)
  {
    return;
  }
  const bool colour = info->GetArrayInformation("rgb", vtkDataObject::POINT) != nullptr;
  vtkSMProxy* proxy = repr->getProxy();
  vtkSMPropertyHelper colorBy(proxy, "ColorArrayName", true);
  const char* shown = colorBy.GetInputArrayNameToProcess();
  const std::string now = shown ? shown : "";
  const bool mapped = vtkSMPropertyHelper(proxy, "MapScalars", true).GetAsInt() != 0;
  if ((colour && now == "rgb" && !mapped) || (!colour && now == "intensity"))
  {
    return;
  }
  if (!now.empty() && now != "rgb" && now != "intensity")
  {
    return;
  }
  SetColouring(proxy, colour);
  this->log(colour ? "colour-rgb" : "colour-intensity");
}

//------------------------------------------------------------------------------
bool pqSchlierenFollower::refining() const
{
  return this->RefineTimer.isActive() || (this->Progressive && !this->Stopped) ||
    (this->following() && !this->Stopped && this->RestTimer.isActive());
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::startImage(const char* why, bool keepPasses)
{
  // The one rule of every image the GUI starts (an Apply, Undo, Load State, a time step; the
  // camera's own handler does the same): the first InteractivePasses passes in the update that
  // follows, the rest up to the Passes asked for in chunks between which the event loop runs.
  // PassLimit holds the chunk's end while the refinement runs and goes back to 0 (no limit)
  // when it converges or is stopped, so it never caps an image in silence.
  if (!this->Image)
  {
    return;
  }
  vtkSMProxy* proxy = this->Image->getProxy();
  this->Target = std::max(1, this->askedPasses());
  this->RefineTimer.stop();
  this->LastChunk = 1;
  this->Stopped = false;
  const int first = std::min(this->Target, InteractivePassesOf(proxy));
  // a larger Passes alone refines the image shown from the passes it has
  const int from = keepPasses && this->LastPasses < this->Target
    ? std::max(first, this->LastPasses)
    : first;
  if (!keepPasses || this->LastPasses >= this->Target)
  {
    this->LastPasses = 0; // the image shown is not this image
  }
  if (this->Target <= from)
  {
    this->Progressive = false;
    this->setPasses(0);
  }
  else
  {
    this->Progressive = true;
    this->setPasses(from);
  }
  this->log(why);
  Q_EMIT this->stateChanged();
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onTimeChanged()
{
  // a new time step: a new image, when the image's data changes with time
  if (!this->Image || this->Busy)
  {
    return;
  }
  vtkPVDataInformation* info = this->Image->getOutputPort(0)->getDataInformation();
  if (info && info->GetNumberOfTimeSteps() > 1)
  {
    this->startImage("time", false);
  }
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onCameraModified()
{
  auto* camera = vtkCamera::SafeDownCast(this->Camera);
  if (!camera || !this->Image || !this->following())
  {
    return;
  }
  if (this->Busy)
  {
    // not inside our own update: once it is done
    QTimer::singleShot(0, this, SLOT(onCameraModified()));
    return;
  }
  double position[3], focal[3], up[3], direction[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  double norm = 0;
  for (int i = 0; i < 3; ++i)
  {
    direction[i] = focal[i] - position[i];
    norm += direction[i] * direction[i];
  }
  norm = std::sqrt(norm);
  if (!(norm > 0))
  {
    return;
  }
  for (double& c : direction)
  {
    c /= norm;
  }
  vtkSMProxy* proxy = this->Image->getProxy();
  double d[3], u[3];
  vtkSMPropertyHelper(proxy, "ViewDirection").Get(d, 3);
  vtkSMPropertyHelper(proxy, "ViewUp").Get(u, 3);
  double change = 0;
  for (int i = 0; i < 3; ++i)
  {
    change = std::max({ change, std::abs(d[i] - direction[i]), std::abs(u[i] - up[i]) });
  }
  if (change < SameDirection)
  {
    return; // a zoom or a pan: the image stays
  }
  // a new view: back to the interactive passes (cancels the refinement in progress)
  const bool cancelled = this->RefineTimer.isActive();
  this->RefineTimer.stop();
  this->LastChunk = 1;
  this->Stopped = false;
  this->LastPasses = 0;
  SCOPED_UNDO_EXCLUDE(); // the camera's own (Camera Undo has the camera)
  this->Guard = true;
  vtkSMPropertyHelper(proxy, "ViewDirection").Set(direction, 3);
  vtkSMPropertyHelper(proxy, "ViewUp").Set(up, 3);
  this->Guard = false;
  this->setPasses(
    std::min(this->Target, InteractivePassesOf(proxy)));
  const double scale = InteractiveScaleOf(proxy);
  if (scale > 0 && scale < 1)
  {
    // a coarser film while the view turns: fewer rays per pass
    int coarse[2];
    for (int i = 0; i < 2; ++i)
    {
      coarse[i] = std::max(8, static_cast<int>(std::lround(this->FullResolution[i] * scale)));
    }
    if (!this->Coarse && this->SecondsPerPass > 0)
    {
      this->SecondsPerPass *= double(coarse[0]) * coarse[1] /
        (double(this->FullResolution[0]) * this->FullResolution[1]);
    }
    this->Guard = true;
    vtkSMPropertyHelper(proxy, "Resolution").Set(coarse, 2);
    this->Guard = false;
    this->Coarse = true;
  }
  proxy->UpdateVTKObjects();
  if (cancelled)
  {
    this->log("cancelled");
    Q_EMIT this->stateChanged();
  }
  this->RestTimer.start(RestMilliseconds);
  if (!this->RetracePending)
  {
    // coalesced: one trace for the mouse moves queued meanwhile
    this->RetracePending = true;
    QTimer::singleShot(0, this, SLOT(retrace()));
  }
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::retrace()
{
  if (this->Busy || !Idle())
  {
    QTimer::singleShot(20, this, SLOT(retrace()));
    return;
  }
  this->RetracePending = false;
  if (this->Image)
  {
    this->update("retrace");
  }
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::update(const char* what)
{
  QElapsedTimer clock;
  clock.start();
  const int before = this->LastPasses;
  // our chunks are short: no progress bar for them, so that ParaView neither blocks the mouse
  // (a new drag) nor processes events inside the trace
  pqProgressManager* progress = pqApplicationCore::instance()->getProgressManager();
  progress->lockProgress(this);
  this->Busy = true;
  this->Image->updatePipeline();
  this->Busy = false;
  progress->unlockProgress(this);
  const double seconds = clock.nsecsElapsed() * 1e-9;
  const int now = this->passes();
  // the filter traced only the passes it did not have (all of them after a new view)
  const int traced = (now > before && std::strcmp(what, "refine") == 0) ? now - before : now;
  this->SecondsPerPass = seconds / std::max(1, traced);
  this->LastPasses = now;
  vtkPVDataInformation* info = this->Image->getOutputPort(0)->getDataInformation();
  double* b = info ? info->GetBounds() : nullptr;
  if (b && (b[0] != this->FilmBounds[0] || b[1] != this->FilmBounds[1] ||
             b[2] != this->FilmBounds[2] || b[3] != this->FilmBounds[3]))
  {
    this->fitImageView();
  }
  if (this->ImageView)
  {
    this->ImageView->render();
  }
  if (std::strcmp(what, "refine") == 0)
  {
    // the Passes field keeps the target; the passes done are said here
    StatusMessage(QString("%1: %2 of %3 passes, Ctrl+Alt+S stops")
                    .arg(this->Image->getSMName())
                    .arg(now)
                    .arg(this->Target));
  }
  this->log(what);
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::refineStep()
{
  if (!this->Image || !this->refinable() || this->Stopped)
  {
    this->RefineTimer.stop();
    this->Progressive = false;
    return;
  }
  if (this->Busy || !Idle())
  {
    return; // the next tick
  }
  if (this->Loading.isValid())
  {
    // Load State: ParaView lays out the state's views after its first update; chunks that
    // follow each other at once would hold that back to the end of the refinement. The chunks
    // start once the image view is on the screen (or after 10 s, a view in a hidden tab).
    QWidget* widget = this->ImageView ? this->ImageView->widget() : nullptr;
    if (!(widget && widget->isVisible()) && this->Loading.elapsed() < 10000)
    {
      return;
    }
    this->Loading.invalidate();
  }
  const int now = this->LastPasses; // the passes of the image shown (0: none on this film yet)
  if (now >= this->Target)
  {
    this->RefineTimer.stop();
    this->Progressive = false;
    // no limit left behind: the filter's Passes is the image's (the next update traces nothing)
    this->setPasses(0);
    this->log("converged");
    Q_EMIT this->stateChanged();
    return;
  }
  // sized from the last measured pass time, growing at most twofold from chunk to chunk (one
  // short measurement must not buy a long chunk that Stop would wait for)
  int chunk = this->SecondsPerPass > 0
    ? std::max(1, static_cast<int>(ChunkSeconds / this->SecondsPerPass))
    : 1;
  chunk = std::min(chunk, 2 * this->LastChunk);
  this->LastChunk = chunk;
  this->setPasses(std::min(this->Target, now + chunk));
  this->Image->getProxy()->UpdateVTKObjects();
  this->update("refine");
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onPropertyModified(vtkObject* property)
{
  // A property of the image changed. Pushed by the GUI (the Properties panel's Apply, while the
  // proxy is modified or not yet applied; Undo and Redo; Load State) or while the image follows
  // the camera: a new image by the one rule (startImage), whether Follow Camera is on or off.
  // ParaView runs the trace that follows as one pipeline update that blocks the GUI's input to
  // its end, so that update traces the interactive passes only. A script's change to an applied
  // image is traced as it asks, in one update, with no limit.
  if (this->Guard || this->Busy || !this->Image)
  {
    return;
  }
  const char* name =
    this->Image->getProxy()->GetPropertyName(vtkSMProperty::SafeDownCast(property));
  if (!name)
  {
    return;
  }
  static const char* const ignored[] = { "FollowCamera", "OpenImageView", "InteractivePasses",
    "InteractiveScale", "PassLimit" };
  for (const char* other : ignored)
  {
    if (std::strcmp(name, other) == 0)
    {
      return;
    }
  }
  const bool passes = std::strcmp(name, "Passes") == 0;
  pqApplicationCore* core = pqApplicationCore::instance();
  pqUndoStack* undo = core->getUndoStack();
  const bool gui = this->Image->modifiedState() != pqProxy::UNMODIFIED ||
    (undo && (undo->getInUndo() || undo->getInRedo())) || core->isLoadingState() ||
    this->following();
  if (!gui)
  {
    this->Target = std::max(1, this->askedPasses());
    this->RefineTimer.stop();
    this->Progressive = false;
    this->Stopped = false;
    this->setPasses(0);
    this->log("script");
    Q_EMIT this->stateChanged();
    return;
  }
  if (!passes)
  {
    // the same Apply (or Undo) may change Passes too: the image is new all the same
    this->NewImage = true;
    QTimer::singleShot(0, this, [this]() { this->NewImage = false; });
  }
  const bool keep = passes && !this->NewImage;
  this->startImage(core->isLoadingState() ? "loading" : (passes ? "target" : "progressive"), keep);
  if (core->isLoadingState())
  {
    this->Loading.start();
  }
  if (keep && this->Progressive && this->following() &&
    this->Image->modifiedState() == pqProxy::UNMODIFIED)
  {
    // a script's larger Passes while following: no update may follow, the chunks start here
    this->RestTimer.start(0);
  }
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onFollowModified()
{
  if (!this->Image)
  {
    return;
  }
  if (this->following())
  {
    this->Target = std::max(1, this->askedPasses());
    if (!this->View3D)
    {
      auto* view = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
      if (view && view != this->ImageView)
      {
        this->View3D = view;
      }
    }
    this->watchCamera(this->View3D);
    this->log("follow");
    this->onCameraModified();
    if (!this->RetracePending)
    {
      this->RestTimer.start(0);
    }
  }
  else
  {
    this->RefineTimer.stop();
    this->RestTimer.stop();
    if (this->Coarse)
    {
      this->restoreResolution();
    }
    this->log("unfollow");
  }
  Q_EMIT this->stateChanged();
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::restoreResolution()
{
  if (!this->Coarse || !this->Image)
  {
    return;
  }
  vtkSMProxy* proxy = this->Image->getProxy();
  int coarse[2];
  vtkSMPropertyHelper(proxy, "Resolution").Get(coarse, 2);
  SCOPED_UNDO_EXCLUDE();
  this->Guard = true;
  vtkSMPropertyHelper(proxy, "Resolution").Set(this->FullResolution, 2);
  this->Guard = false;
  this->Coarse = false;
  // the full film traces every pass again, with more rays per pass
  if (this->SecondsPerPass > 0)
  {
    this->SecondsPerPass *= double(this->FullResolution[0]) * this->FullResolution[1] /
      std::max(1.0, double(coarse[0]) * coarse[1]);
  }
  this->LastPasses = 0;
  this->setPasses(
    std::min(this->Target, InteractivePassesOf(proxy)));
  proxy->UpdateVTKObjects();
  this->LastPasses = 0;
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::onResolutionModified()
{
  if (!this->Guard && this->Image)
  {
    vtkSMPropertyHelper(this->Image->getProxy(), "Resolution").Get(this->FullResolution, 2);
    this->Coarse = false;
  }
}

//------------------------------------------------------------------------------
void pqSchlierenFollower::stop()
{
  const bool was = this->refining();
  this->RefineTimer.stop();
  this->RestTimer.stop();
  this->Stopped = true;
  this->Progressive = false;
  if (was && this->Image)
  {
    const int done = this->LastPasses; // the passes of the image shown
    const int asked = this->Target;
    if (done > 0 && done < asked && !this->Coarse)
    {
      // The image keeps the passes traced, and the panel says so: Passes becomes them, and no
      // limit is left behind (a larger Passes applied refines from here; a saved state holds
      // this image's passes).
      vtkSMProxy* proxy = this->Image->getProxy();
      SCOPED_UNDO_EXCLUDE(); // the image's passes said, not a change of the user's to undo
      this->Guard = true;
      vtkSMPropertyHelper(proxy, "Passes").Set(done);
      vtkSMPropertyHelper(proxy, "PassLimit").Set(0);
      proxy->UpdateVTKObjects();
      this->Guard = false;
      this->Target = done;
      StatusMessage(QString("%1: stopped at %2 of %3 passes; Passes is now %2")
                      .arg(this->Image->getSMName())
                      .arg(done)
                      .arg(asked));
    }
    else
    {
      StatusMessage(QString("%1: refinement stopped at %2 of %3 passes")
                      .arg(this->Image->getSMName())
                      .arg(this->passes())
                      .arg(asked));
    }
  }
  this->log("stopped");
  Q_EMIT this->stateChanged();
}

//==============================================================================
pqSchlierenToolbar::pqSchlierenToolbar(QWidget* parent)
  : QToolBar("Schlieren", parent)
{
  this->setObjectName("SchlierenToolbar");
  new pqSchlierenMessages(this);
#ifdef SCHLIEREN_OWN_HELP
  // ParaView 5.12/5.13 with Qt 6: the help pages the plugin macro left out (SchlierenHelp.h)
  SchlierenRegisterHelp();
#endif
  if (std::getenv("SCHLIEREN_GUI_TRACE"))
  {
    std::fprintf(stderr, "schlieren-gui %.6f toolbar created\n", QDateTime::currentMSecsSinceEpoch() / 1000.0);
  }
  this->FollowAction = this->addAction(QIcon(":/Schlieren/Icons/FollowCamera.svg"), "Follow Camera");
  this->FollowAction->setObjectName("actionSchlierenFollowCamera");
  this->FollowAction->setCheckable(true);
  this->FollowAction->setShortcut(QKeySequence("Ctrl+Alt+F"));
  this->FollowAction->setToolTip("The active Schlieren Image follows the 3D view's camera: a few "
                                 "passes while the view turns, refined to Passes when it rests "
                                 "(the FollowCamera property; Ctrl+Alt+F)");
  this->StopAction = this->addAction(QIcon(":/Schlieren/Icons/StopRefinement.svg"), "Stop Refinement");
  this->StopAction->setObjectName("actionSchlierenStop");
  this->StopAction->setShortcut(QKeySequence("Ctrl+Alt+S"));
  this->StopAction->setToolTip(
    "Stops the refinement in progress; the image keeps the passes done (Ctrl+Alt+S)");
  this->ViewAction = this->addAction(QIcon(":/Schlieren/Icons/SchlierenImage.svg"), "Schlieren View");
  this->ViewAction->setObjectName("actionSchlierenView");
  this->ViewAction->setToolTip("Shows the active Schlieren Image in a 2D view beside the 3D view");
  QObject::connect(this->FollowAction, SIGNAL(toggled(bool)), this, SLOT(toggleFollow(bool)));
  QObject::connect(this->StopAction, SIGNAL(triggered()), this, SLOT(stopRefinement()));
  QObject::connect(this->ViewAction, SIGNAL(triggered()), this, SLOT(showImageView()));

  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model, SIGNAL(sourceAdded(pqPipelineSource*)), this,
    SLOT(onSourceAdded(pqPipelineSource*)));
  QObject::connect(model, SIGNAL(preSourceRemoved(pqPipelineSource*)), this,
    SLOT(onSourceRemoved(pqPipelineSource*)));
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source);
  }
  QObject::connect(&pqActiveObjects::instance(), SIGNAL(sourceChanged(pqPipelineSource*)), this,
    SLOT(updateActions()));
  pqProgressManager* progress = pqApplicationCore::instance()->getProgressManager();
  QObject::connect(progress, &pqProgressManager::progressStartEvent, this, []() { ++UpdatesInProgress; });
  QObject::connect(progress, &pqProgressManager::progressEndEvent, this,
    []() { UpdatesInProgress = std::max(0, UpdatesInProgress - 1); });
  this->updateActions();
}

//------------------------------------------------------------------------------
pqSchlierenToolbar::~pqSchlierenToolbar() = default;

//------------------------------------------------------------------------------
void pqSchlierenToolbar::onSourceAdded(pqPipelineSource* source)
{
  if (source && source->getProxy() &&
    source->getProxy()->GetXMLName() == std::string("SchlierenPhotograph"))
  {
    QObject::connect(source, &pqPipelineSource::representationAdded, this,
      [](pqPipelineSource*, pqDataRepresentation* repr, int) { ColourPhotograph(repr); });
    QObject::connect(source, QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated), this,
      [](pqPipelineSource* photograph) {
        for (int port = 0; port < photograph->getNumberOfOutputPorts(); ++port)
        {
          for (pqDataRepresentation* repr : photograph->getRepresentations(port, nullptr))
          {
            ColourPhotograph(repr);
          }
        }
      });
    return;
  }
  if (!IsSchlierenImage(source) || this->Followers.contains(source))
  {
    return;
  }
  auto* follower = new pqSchlierenFollower(source, this);
  follower->log("tracked");
  this->Followers.insert(source, follower);
  QObject::connect(follower, SIGNAL(stateChanged()), this, SLOT(updateActions()));
  this->updateActions();
}

//------------------------------------------------------------------------------
void pqSchlierenToolbar::onSourceRemoved(pqPipelineSource* source)
{
  if (auto follower = this->Followers.take(source))
  {
    follower->closeImageView();
    delete follower;
  }
  this->updateActions();
}

//------------------------------------------------------------------------------
pqSchlierenFollower* pqSchlierenToolbar::active() const
{
  pqPipelineSource* source = pqActiveObjects::instance().activeSource();
  if (source && this->Followers.contains(source))
  {
    return this->Followers.value(source);
  }
  // the one schlieren image of the session, when another source is selected
  return this->Followers.size() == 1 ? this->Followers.first().data() : nullptr;
}

//------------------------------------------------------------------------------
void pqSchlierenToolbar::updateActions()
{
  pqSchlierenFollower* follower = this->active();
  this->FollowAction->setEnabled(follower != nullptr);
  this->FollowAction->blockSignals(true);
  this->FollowAction->setChecked(follower && follower->following());
  this->FollowAction->blockSignals(false);
  // Stop Refinement: only while an image refines
  bool refining = false;
  for (const auto& f : this->Followers)
  {
    refining = refining || (f && f->refining());
  }
  if (std::getenv("SCHLIEREN_GUI_TRACE") && refining != this->StopAction->isEnabled())
  {
    std::fprintf(stderr, "schlieren-gui %.6f actions toolbar stop=%d\n",
      QDateTime::currentMSecsSinceEpoch() / 1000.0, refining ? 1 : 0);
  }
  this->StopAction->setEnabled(refining);
  this->ViewAction->setEnabled(follower != nullptr);
}

//------------------------------------------------------------------------------
void pqSchlierenToolbar::toggleFollow(bool on)
{
  if (pqSchlierenFollower* follower = this->active())
  {
    follower->setFollowing(on);
  }
  this->updateActions();
}

//------------------------------------------------------------------------------
void pqSchlierenToolbar::stopRefinement()
{
  for (const auto& f : this->Followers)
  {
    if (f)
    {
      f->stop();
    }
  }
}

//------------------------------------------------------------------------------
void pqSchlierenToolbar::showImageView()
{
  if (pqSchlierenFollower* follower = this->active())
  {
    follower->openImageView(qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView()));
  }
}
