// SPDX-License-Identifier: BSD-3-Clause
#include "pqSchlierenMessages.h"

#include "pqActiveObjects.h"
#include "pqCoreUtilities.h"
#include "pqOutputWidget.h"

#include <QAction>
#include <QDateTime>
#include <QDockWidget>
#include <QStringList>
#include <QTimer>
#include <QUrl>
#include <QVariant>
#include <QWidget>

#include <cstdio>
#include <cstdlib>

namespace
{
// The filters whose input must be an image, and what to do when it is not.
const char* const ImageFilters[] = { "SchlierenImage", "RefractionOctree" };
// What to do comes first: the status bar shows about 70 characters beside the progress bar at
// 1280 pixels (the longer hint of before was cut at "...apply RefractiveIndex f").
const char* const ImageHint = ": apply RefractiveIndex first (Filters > Schlieren), which "
                              "resamples any grid onto an image with n_minus_1";
}

//------------------------------------------------------------------------------
pqSchlierenMessages::pqSchlierenMessages(QObject* parent)
  : QObject(parent)
{
  this->hookOutput(100);
  // the menus' enabled state follows the active source (pqFiltersMenuReaction)
  QObject::connect(&pqActiveObjects::instance(), &pqActiveObjects::sourceChanged, this,
    [this]() { QTimer::singleShot(0, this, [this]() { this->hintActions(); }); });
  QTimer::singleShot(0, this, [this]() { this->hintActions(); });
}

//------------------------------------------------------------------------------
void pqSchlierenMessages::hookOutput(int tries)
{
  QWidget* main = pqCoreUtilities::mainWidget();
  pqOutputWidget* output = main ? main->findChild<pqOutputWidget*>() : nullptr;
  if (!output)
  {
    if (tries > 0)
    {
      QTimer::singleShot(100, this, [this, tries]() { this->hookOutput(tries - 1); });
    }
    return;
  }
  if (this->OutputHooked)
  {
    return;
  }
  this->OutputHooked = true;
  output->suppress(QStringList() << "Algorithm vtkSchlierenImage" << "Algorithm vtkRefractiveIndex"
                                 << "Algorithm vtkRefractionOctree"
                                 << "Algorithm vtkRefractiveScene"
                                 // the representation of an image that failed: the same again
                                 << "Algorithm vtkPVGeometryFilter");
  // Model Automatic's choice decides the whole image: the Output Messages open to show it (once
  // per new choice; ParaView opens them by itself only for warnings and errors)
  QObject::connect(output, &pqOutputWidget::messageDisplayed, this,
    [this, output](const QString& message, int) {
      const int at = message.indexOf("RefractiveIndex: Model Automatic chose");
      if (at < 0 || message.mid(at) == this->LastChoice)
      {
        return;
      }
      this->LastChoice = message.mid(at);
      for (QWidget* w = output->parentWidget(); w; w = w->parentWidget())
      {
        if (auto* dock = qobject_cast<QDockWidget*>(w))
        {
          dock->show();
          dock->raise();
          if (std::getenv("SCHLIEREN_GUI_TRACE"))
          {
            std::fprintf(stderr, "schlieren-gui %.6f output-shown\n",
              QDateTime::currentMSecsSinceEpoch() / 1000.0);
            std::fflush(stderr);
          }
          break;
        }
      }
    });
  if (std::getenv("SCHLIEREN_GUI_TRACE"))
  {
    QObject::connect(output, &pqOutputWidget::messageDisplayed, this,
      [](const QString& message, int type) {
        std::fprintf(stderr, "schlieren-gui %.6f message %d %s\n",
          QDateTime::currentMSecsSinceEpoch() / 1000.0, type,
          QUrl::toPercentEncoding(message.trimmed()).constData());
        std::fflush(stderr);
      });
  }
}

//------------------------------------------------------------------------------
void pqSchlierenMessages::hintActions()
{
  QWidget* main = pqCoreUtilities::mainWidget();
  if (!main)
  {
    return;
  }
  for (QAction* action : main->findChildren<QAction*>())
  {
    const QStringList data = action->data().toStringList();
    bool ours = false;
    for (const char* name : ImageFilters)
    {
      ours = ours || data.contains(QLatin1String(name));
    }
    if (!ours)
    {
      continue;
    }
    if (!action->property("schlierenHinted").toBool())
    {
      action->setProperty("schlierenHinted", true);
      QObject::connect(action, &QAction::changed, this, [this, action]() { this->hint(action); });
    }
    this->hint(action);
  }
}

//------------------------------------------------------------------------------
void pqSchlierenMessages::hint(QAction* action)
{
  // ParaView's tip for an input of the wrong type; it is set again whenever the state changes
  const QString tip = action->statusTip();
  if (!action->isEnabled() && tip.startsWith("Input must be") && !tip.contains("RefractiveIndex"))
  {
    action->setStatusTip(tip + ImageHint);
    if (std::getenv("SCHLIEREN_GUI_TRACE"))
    {
      std::fprintf(stderr, "schlieren-gui %.6f hint %s %s\n",
        QDateTime::currentMSecsSinceEpoch() / 1000.0,
        QUrl::toPercentEncoding(action->text()).constData(),
        QUrl::toPercentEncoding(action->statusTip()).constData());
      std::fflush(stderr);
    }
  }
}
