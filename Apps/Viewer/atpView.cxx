// atp-view: the desktop viewer of ATP models (also run as `atp view`).
#include "atpCommandLine.h"
#include "atpModelBuild.h"
#include "atpOutputPath.h"
#include "atpVolumeSlabs.h"
#include "atpPropertiesPanel.h"
#include "atpViewerWindow.h"

#include "QVTKOpenGLNativeWidget.h"

#include <QApplication>
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QSpinBox>
#include <QSurfaceFormat>
#include <QTimer>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>
#include <cstdlib>

namespace
{

QtMessageHandler QtsHandler = nullptr;

/// Qt ends the process with abort() when it cannot open a window (a display it cannot reach):
/// like any other error of a session, a line and exit code 1 instead.
void ExitOnFatalMessage(QtMsgType type, const QMessageLogContext& context, const QString& message)
{
  if (type != QtFatalMsg)
  {
    QtsHandler(type, context, message);
    return;
  }
  const QByteArray firstLine = message.section('\n', 0, 0).toLocal8Bit();
  std::fprintf(stderr, "atp view: error: cannot open a window: %s\n", firstLine.constData());
  std::_Exit(1);
}

bool Set(const char* variable)
{
  const char* value = std::getenv(variable);
  return value && *value;
}

atp::CommandLine Options()
{
  atp::CommandLine cl("view",
    "Shows a multiresolution model (.atp) view-dependently, or builds one first from a mesh\n"
    "or from the isosurface of a volume (with a progress dialog). Drag with the left button to rotate, the right button or the\n"
    "wheel to zoom, the middle button to pan. The options below set the panel's properties\n"
    "and script a session: play a camera path, record one, save a screenshot and quit.");
  cl.AddPositional("MODEL", "a model (.atp), or a mesh (.ply, .obj, .stl, .vtp) or volume (.nii,\n"
    "      .nii.gz, .vti) to build one from", true);
  cl.AddOption("output", "o", "OUT.atp", "where the model of a mesh or volume is built",
    "the input's name with .atp, beside it");
  cl.AddOption("iso", "", "VALUE", "iso value of a volume's surface (needed for volumes)");
  cl.AddOption("tolerance", "", "PX", "screen-space tolerance in pixels", "1");
  cl.AddOption("cache-budget", "", "MiB", "GPU memory for patches", "512");
  cl.AddFlag("no-prefetch", "no speculative prefetching");
  cl.AddFlag("backface-culling", "cull patches facing away");
  cl.AddFlag("patch-coloring", "one color per patch");
  cl.AddOption("size", "", "WxH", "size of the render view", "as the window allows");
  cl.AddOption("play", "", "PATH.camera", "fly along a recorded camera path once the model is open");
  cl.AddOption("record", "", "PATH.camera",
    "record the camera from the moment the model opens; written when the window closes");
  cl.AddOption("screenshot", "", "FILE.png",
    "once the model is open (and the path played), save the converged view and quit");
  return cl;
}

/// Every file the session writes is checked before it starts, not when it ends: its name says
/// what it holds, and none may replace an input or another of them (a screenshot over the
/// model, a recording over the path it plays).
void CheckOutputs(const atp::CommandLine& cl)
{
  std::vector<std::string> taken; // the inputs, then each output checked
  if (cl.PositionalCount() > 0)
  {
    taken.push_back(cl.Positional(0));
  }
  if (cl.Has("play"))
  {
    taken.push_back(cl.Get("play"));
  }
  const std::pair<const char*, const char*> outputs[] = { { "output", ".atp" }, { "screenshot", ".png" },
    { "record", ".camera" } };
  for (const auto& [option, extension] : outputs)
  {
    if (!cl.Has(option))
    {
      continue;
    }
    const std::string& path = cl.Get(option);
    const std::string name = std::string("--") + option + " " + path + ": ";
    if (atp::FileExtension(path) != extension)
    {
      throw atp::UsageError(name + "a name ending in " + extension);
    }
    // Their names end differently, so outputs never meet; an input exists, so it is known.
    const std::string problem = atp::OutputPathProblem(path, taken);
    if (!problem.empty())
    {
      throw atp::UsageError(name + problem);
    }
    taken.push_back(path);
  }
}

}

int main(int argc, char** argv)
{
  // Everything is checked before Qt starts, so that mistakes are reported without a display.
  atp::CommandLine cl = Options();
  double tolerance = 1, isoValue = 0;
  long long cacheBudget = 512;
  int width = 0, height = 0;
  try
  {
    if (!cl.Parse(std::vector<std::string>(argv + 1, argv + argc)))
    {
      return 0;
    }
    tolerance = cl.Has("tolerance") ? cl.GetNumber("tolerance", 0.1, 1000) : tolerance;
    cacheBudget = cl.Has("cache-budget") ? cl.GetInteger("cache-budget", 1, 1 << 20) : cacheBudget;
    if (cl.Has("size"))
    {
      cl.GetSize("size", width, height);
    }
    const bool volume =
      cl.PositionalCount() > 0 && atp::IsVolumeFileName(cl.Positional(0));
    if (volume && !cl.Has("iso"))
    {
      throw atp::UsageError("a volume needs --iso VALUE (the surface's iso value)");
    }
    isoValue = cl.Has("iso") ? cl.GetNumber("iso", -1e300, 1e300) : isoValue;
    if (cl.Has("screenshot") && cl.PositionalCount() == 0)
    {
      throw atp::UsageError("--screenshot needs a MODEL");
    }
    CheckOutputs(cl);
  }
  catch (const atp::UsageError& e)
  {
    std::fprintf(stderr, "atp view: %s\n", e.what());
    return 2;
  }

  if (!Set("DISPLAY") && !Set("WAYLAND_DISPLAY") && !Set("QT_QPA_PLATFORM"))
  {
    std::fprintf(stderr, "atp view: error: no display to open a window on (DISPLAY is not set): run "
                         "it on a desktop, or under xvfb-run -a\n");
    return 1;
  }
  QtsHandler = qInstallMessageHandler(ExitOnFatalMessage);
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QApplication::setApplicationName("atp-view");
  atp::ViewerWindow window;
  // Through the panel's widgets, so the panel shows what the mapper does.
  atp::PropertiesPanel* properties = window.Properties();
  properties->TolerancePixels()->setValue(tolerance);
  properties->CacheBudgetMiB()->setValue(int(cacheBudget));
  properties->Prefetching()->setChecked(!cl.Has("no-prefetch"));
  properties->BackfaceCulling()->setChecked(cl.Has("backface-culling"));
  properties->PatchColoring()->setChecked(cl.Has("patch-coloring"));
  if (width > 0)
  {
    window.View()->setFixedSize(width, height);
  }

  // A scripted session (--screenshot) ends with an error instead of waiting on a message box.
  const bool scripted = cl.Has("screenshot");
  int status = 0;
  if (scripted)
  {
    QObject::connect(&window, &atp::ViewerWindow::ErrorShown, [&](const QString& message) {
      std::fprintf(stderr, "atp view: error: %s\n", message.toLocal8Bit().constData());
      status = 1;
      application.exit(1);
    });
    QObject::connect(&window, &atp::ViewerWindow::WarningShown, [](const QString& message) {
      std::fprintf(stderr, "atp view: warning: %s\n", message.toLocal8Bit().constData());
    });
    // A screenshot with a region drawn coarser than asked is not the picture asked for.
    QObject::connect(&window, &atp::ViewerWindow::PatchErrorShown, [&](const QString& message) {
      std::fprintf(stderr, "atp view: error: %s\n", message.toLocal8Bit().constData());
      status = 1;
      application.exit(1);
    });
  }
  const auto saveWhenConverged = [&] {
    auto* poll = new QTimer(&window);
    QObject::connect(poll, &QTimer::timeout, [&, poll] {
      if (window.Converged())
      {
        poll->stop();
        status = window.SaveScreenshot(QString::fromStdString(cl.Get("screenshot"))) ? 0 : 1;
        application.exit(status);
      }
    });
    poll->start(20);
  };
  QObject::connect(&window, &atp::ViewerWindow::ModelOpened, [&] {
    if (cl.Has("record"))
    {
      window.StartRecording();
    }
    if (cl.Has("play"))
    {
      if (window.PlayCameraPath(QString::fromStdString(cl.Get("play"))) && scripted)
      {
        QObject::connect(&window, &atp::ViewerWindow::PlaybackFinished, saveWhenConverged);
      }
      return;
    }
    if (scripted)
    {
      saveWhenConverged();
    }
  });
  QObject::connect(&application, &QApplication::aboutToQuit, [&] {
    if (window.Recording())
    {
      window.StopRecording(QString::fromStdString(cl.Get("record")));
    }
  });

  window.show();
  if (cl.PositionalCount() > 0)
  {
    const QString output = cl.Has("output") ? QString::fromStdString(cl.Get("output")) : QString();
    // Once the event loop runs, so the window is on screen behind a build's progress dialog.
    QTimer::singleShot(0, &window, [&, output] {
      window.OpenFile(QString::fromStdString(cl.Positional(0)), output, isoValue);
    });
  }
  const int result = application.exec();
  return status ? status : result;
}
