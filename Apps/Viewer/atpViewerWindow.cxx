#include "atpViewerWindow.h"

#include "atpErrorCapture.h"
#include "atpVtkErrorMessage.h"
#include "atpModelBuild.h"
#include "atpVolumeSlabs.h"
#include "atpPropertiesPanel.h"
#include "atpRenderStatistics.h"
#include "atpStatisticsPanel.h"
#include "vtkATPMapper.h"
#include "vtkATPReader.h"

#include "QVTKOpenGLNativeWidget.h"
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkInteractorObserver.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <QAction>
#include <QCloseEvent>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QToolBar>

#include <exception>

namespace atp
{
namespace
{

/// ParaView's default background.
constexpr double Background[3] = { 0.32, 0.34, 0.43 };

}

ViewerWindow::ViewerWindow(QWidget* parent)
  : QMainWindow(parent)
  , RenderView(new QVTKOpenGLNativeWidget)
  , PropertiesDock(new PropertiesPanel(ModelMapper, Actor, SceneRenderer))
  , StatisticsDock(new StatisticsPanel)
{
  setWindowTitle(tr("ATP Viewer"));
  RenderView->setObjectName("renderView");
  RenderView->setRenderWindow(RenderWindow);
  RenderWindow->AddRenderer(SceneRenderer);
  SceneRenderer->SetBackground(Background[0], Background[1], Background[2]);
  Actor->SetMapper(ModelMapper);
  vtkNew<vtkInteractorStyleTrackballCamera> trackball;
  RenderView->interactor()->SetInteractorStyle(trackball);
  setCentralWidget(RenderView);

  const auto dock = [this](const QString& name, const QString& title, QWidget* panel) {
    auto* widget = new QDockWidget(title, this);
    widget->setObjectName(name);
    widget->setWidget(panel);
    widget->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
    addDockWidget(Qt::LeftDockWidgetArea, widget);
  };
  dock("propertiesDock", tr("Properties"), PropertiesDock);
  dock("statisticsDock", tr("Statistics"), StatisticsDock);
  CreateActions();
  statusBar()->showMessage(tr("Open a model (.atp) or build one from a mesh or a volume"));
  resize(1100, 750);

  connect(PropertiesDock, &PropertiesPanel::Changed, this, &ViewerWindow::Render);
  // One render per timer tick: the view shows what has arrived while the cut converges.
  ConvergenceTimer.setSingleShot(true);
  ConvergenceTimer.setInterval(15);
  connect(&ConvergenceTimer, &QTimer::timeout, this, &ViewerWindow::Render);
  PlaybackTimer.setInterval(15);
  connect(&PlaybackTimer, &QTimer::timeout, this, &ViewerWindow::PlaybackStep);

  vtkNew<vtkCallbackCommand> onRendered;
  onRendered->SetClientData(this);
  onRendered->SetCallback([](vtkObject*, unsigned long, void* client, void*) {
    static_cast<ViewerWindow*>(client)->Rendered();
  });
  SceneRenderer->AddObserver(vtkCommand::EndEvent, onRendered);
  // A camera still for a while before a drag: keep the pause in the recorded path.
  vtkNew<vtkCallbackCommand> onInteraction;
  onInteraction->SetClientData(this);
  onInteraction->SetCallback([](vtkObject*, unsigned long, void* client, void*) {
    auto* self = static_cast<ViewerWindow*>(client);
    if (self->IsRecording)
    {
      self->Path.Record(self->Clock.elapsed() / 1e3, self->SceneRenderer->GetActiveCamera());
    }
  });
  trackball->AddObserver(vtkCommand::StartInteractionEvent, onInteraction);
  // Patches that turn out corrupt while drawing: said once each by the mapper.
  vtkNew<vtkCallbackCommand> onMapperError;
  onMapperError->SetClientData(this);
  onMapperError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* self = static_cast<ViewerWindow*>(client);
    const QString message = QString::fromStdString(VtkErrorMessage(static_cast<const char*>(call)));
    self->statusBar()->showMessage(message);
    emit self->PatchErrorShown(message);
  });
  ModelMapper->AddObserver(vtkCommand::ErrorEvent, onMapperError);
}

ViewerWindow::~ViewerWindow()
{
  delete Build; // cancels and waits for a build still running
  // The render view, a child widget, outlives the members: no callbacks into a window that is
  // going away.
  SceneRenderer->RemoveAllObservers();
  ModelMapper->RemoveAllObservers();
  RenderView->interactor()->GetInteractorStyle()->RemoveAllObservers();
}

void ViewerWindow::CreateActions()
{
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QMenu* camera = menuBar()->addMenu(tr("&Camera"));
  QToolBar* tools = addToolBar(tr("Main"));
  tools->setObjectName("mainToolBar");
  const auto add = [this, tools](QMenu* menu, const QString& name, const QString& text,
                     QKeySequence keys, auto slot) {
    QAction* action = menu->addAction(text);
    action->setObjectName(name);
    action->setShortcut(keys);
    connect(action, &QAction::triggered, this, slot);
    tools->addAction(action);
    return action;
  };
  add(file, "openModel", tr("&Open Model..."), QKeySequence::Open, &ViewerWindow::ChooseModel);
  BuildAction = add(file, "buildModel", tr("&Build Model..."), QKeySequence(tr("Ctrl+B")),
    &ViewerWindow::ChooseInput);
  add(file, "saveScreenshot", tr("Save &Screenshot..."), QKeySequence(tr("Ctrl+S")),
    &ViewerWindow::ChooseScreenshot);
  file->addSeparator();
  file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);
  tools->addSeparator();
  add(camera, "resetCamera", tr("&Reset Camera"), QKeySequence(tr("R")), &ViewerWindow::ResetCamera);
  RecordAction = camera->addAction(tr("Re&cord Camera Path"));
  RecordAction->setObjectName("recordCameraPath");
  RecordAction->setCheckable(true);
  RecordAction->setShortcut(QKeySequence(tr("Ctrl+R")));
  connect(RecordAction, &QAction::toggled, this, &ViewerWindow::ToggleRecording);
  tools->addAction(RecordAction);
  add(camera, "playCameraPath", tr("&Play Camera Path..."), QKeySequence(tr("Ctrl+P")),
    &ViewerWindow::ChooseCameraPath);
}

void ViewerWindow::ShowError(const QString& title, const QString& message)
{
  ShowMessageBox(QMessageBox::Critical, "errorMessage", title, message);
  emit ErrorShown(message);
}

void ViewerWindow::ShowWarning(const QString& title, const QString& message)
{
  ShowMessageBox(QMessageBox::Warning, "warningMessage", title, message);
  emit WarningShown(message);
}

void ViewerWindow::ShowMessageBox(
  QMessageBox::Icon icon, const char* name, const QString& title, const QString& message)
{
  statusBar()->showMessage(title + ": " + message);
  // Not exec(): the window (and whatever drives it) goes on while the box is up.
  auto* box = new QMessageBox(icon, title, message, QMessageBox::Ok, this);
  box->setObjectName(name);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

void ViewerWindow::OpenFile(const QString& path, const QString& model, double isoValue)
{
  if (QFileInfo(path).suffix().compare("atp", Qt::CaseInsensitive) == 0)
  {
    OpenModel(path);
    return;
  }
  const QFileInfo input(path);
  BuildModel(path, model.isEmpty() ? input.dir().filePath(input.completeBaseName() + ".atp") : model,
    isoValue);
}

bool ViewerWindow::OpenModel(const QString& path)
{
  auto reader = vtkSmartPointer<vtkATPReader>::New();
  // The pipeline's own error ("returned failure") comes after the reader's: not shown.
  const ErrorCapture errors({ reader, reader->GetExecutive() });
  reader->SetFileName(path.toLocal8Bit().constData());
  reader->Update();
  if (!errors.Message().empty() || reader->GetErrorCode())
  {
    ShowError(tr("Cannot open %1").arg(QFileInfo(path).fileName()),
      errors.Message().empty() ? tr("%1: not a valid model").arg(path)
                               : QString::fromStdString(errors.Message()));
    return false;
  }
  Reader = reader;
  ModelMapper->SetInputConnection(Reader->GetOutputPort());
  if (!SceneRenderer->HasViewProp(Actor))
  {
    SceneRenderer->AddActor(Actor);
  }
  setWindowTitle(tr("%1 - ATP Viewer").arg(QFileInfo(path).fileName()));
  statusBar()->showMessage(tr("Opened %1").arg(path));
  ResetCamera();
  emit ModelOpened(path);
  return true;
}

void ViewerWindow::BuildModel(const QString& input, const QString& model, double isoValue)
{
  if (Build)
  {
    return; // one build at a time (the action is disabled meanwhile)
  }
  BuildAction->setEnabled(false);
  statusBar()->showMessage(tr("Building %1 from %2...").arg(model, input));
  Build = new ModelBuild(input, isoValue, model, this);
  connect(Build, &ModelBuild::Finished, this,
    [this](const QString& built, const QString& error, const QString& warning, bool cancelled) {
      Build->deleteLater();
      Build = nullptr;
      BuildAction->setEnabled(true);
      if (cancelled)
      {
        statusBar()->showMessage(tr("Build cancelled"));
      }
      else if (!error.isEmpty())
      {
        ShowError(tr("Cannot build %1").arg(QFileInfo(built).fileName()), error);
      }
      else if (OpenModel(built) && !warning.isEmpty())
      {
        ShowWarning(tr("Built %1 with a warning").arg(QFileInfo(built).fileName()), warning);
      }
    });
}

bool ViewerWindow::SaveScreenshot(const QString& path)
{
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(RenderWindow);
  capture->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  const ErrorCapture errors({ writer });
  writer->SetFileName(path.toLocal8Bit().constData());
  writer->SetInputConnection(capture->GetOutputPort());
  writer->Write();
  if (!errors.Message().empty() || writer->GetErrorCode())
  {
    // VTK's messages do not name the file ("Ran out of disk space; deleting file(s) already
    // written"), and its codes are names, not words.
    const unsigned long code = writer->GetErrorCode();
    ShowError(tr("Cannot save the screenshot"),
      tr("%1: cannot write: %2")
        .arg(path, QString::fromStdString(code ? VtkErrorCodeText(code) : errors.Message())));
    return false;
  }
  statusBar()->showMessage(tr("Saved %1").arg(path));
  return true;
}

void ViewerWindow::StartRecording()
{
  Path = CameraPath();
  Clock.start();
  Path.Record(0, SceneRenderer->GetActiveCamera());
  IsRecording = true;
  const QSignalBlocker quiet(RecordAction);
  RecordAction->setChecked(true);
  statusBar()->showMessage(tr("Recording the camera path..."));
}

bool ViewerWindow::StopRecording(const QString& path)
{
  if (!IsRecording)
  {
    return false;
  }
  Path.Record(Clock.elapsed() / 1e3, SceneRenderer->GetActiveCamera());
  IsRecording = false;
  const QSignalBlocker quiet(RecordAction);
  RecordAction->setChecked(false);
  try
  {
    Path.Save(path.toLocal8Bit().constData());
  }
  catch (const std::exception& e)
  {
    ShowError(tr("Cannot save the camera path"), QString::fromLocal8Bit(e.what()));
    return false;
  }
  statusBar()->showMessage(tr("Saved %1 keyframes to %2").arg(Path.Keyframes().size()).arg(path));
  return true;
}

bool ViewerWindow::PlayCameraPath(const QString& path)
{
  try
  {
    Path = CameraPath::Load(path.toLocal8Bit().constData());
  }
  catch (const std::exception& e)
  {
    ShowError(tr("Cannot play the camera path"), QString::fromLocal8Bit(e.what()));
    return false;
  }
  IsRecording = false;
  Clock.start();
  PlaybackTimer.start();
  statusBar()->showMessage(tr("Playing %1 (%2 s)").arg(path).arg(Path.Duration(), 0, 'f', 1));
  return true;
}

void ViewerWindow::PlaybackStep()
{
  const double time = Clock.elapsed() / 1e3;
  Path.Apply(time, SceneRenderer->GetActiveCamera());
  SceneRenderer->ResetCameraClippingRange();
  Render();
  if (time >= Path.Duration())
  {
    PlaybackTimer.stop();
    statusBar()->showMessage(tr("Camera path played"));
    emit PlaybackFinished();
  }
}

bool ViewerWindow::Converged() const
{
  return Reader && ModelMapper->GetConverged() && !ConvergenceTimer.isActive();
}

void ViewerWindow::Render()
{
  RenderWindow->Render();
}

void ViewerWindow::Rendered()
{
  if (!Reader)
  {
    return;
  }
  StatisticsDock->Show(ModelMapper->GetStatistics(), SceneRenderer->GetLastRenderTimeInSeconds());
  if (IsRecording)
  {
    Path.Record(Clock.elapsed() / 1e3, SceneRenderer->GetActiveCamera());
  }
  if (!ModelMapper->GetConverged())
  {
    ConvergenceTimer.start();
  }
}

void ViewerWindow::ResetCamera()
{
  SceneRenderer->ResetCamera();
  Render();
}

void ViewerWindow::ChooseModel()
{
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Model"), QString(),
    tr("ATP models (*.atp);;All files (*)"));
  if (!path.isEmpty())
  {
    OpenModel(path);
  }
}

void ViewerWindow::ChooseInput()
{
  const QString input = QFileDialog::getOpenFileName(this, tr("Build Model from a Mesh or Volume"),
    QString(), tr("Meshes and volumes (*.ply *.obj *.stl *.vtp *.nii *.nii.gz *.vti);;All files (*)"));
  if (input.isEmpty())
  {
    return;
  }
  double isoValue = 0;
  if (IsVolumeFileName(input.toStdString()))
  {
    bool ok = false;
    isoValue = QInputDialog::getDouble(this, tr("Isosurface"), tr("Iso value of the surface:"),
      LastIsoValue, -1e300, 1e300, 6, &ok);
    if (!ok)
    {
      return;
    }
    LastIsoValue = isoValue;
  }
  const QFileInfo info(input);
  const QString model = QFileDialog::getSaveFileName(this, tr("Save Model As"),
    info.dir().filePath(info.completeBaseName() + ".atp"), tr("ATP models (*.atp)"));
  if (!model.isEmpty())
  {
    BuildModel(input, model, isoValue);
  }
}

void ViewerWindow::ChooseScreenshot()
{
  const QString path =
    QFileDialog::getSaveFileName(this, tr("Save Screenshot"), "screenshot.png", tr("PNG images (*.png)"));
  if (!path.isEmpty())
  {
    SaveScreenshot(path);
  }
}

void ViewerWindow::ToggleRecording(bool on)
{
  if (on)
  {
    StartRecording();
    return;
  }
  const QString path = QFileDialog::getSaveFileName(
    this, tr("Save Camera Path"), "path.camera", tr("Camera paths (*.camera)"));
  if (path.isEmpty())
  {
    IsRecording = false;
    statusBar()->showMessage(tr("Recording discarded"));
    return;
  }
  StopRecording(path);
}

void ViewerWindow::ChooseCameraPath()
{
  const QString path = QFileDialog::getOpenFileName(
    this, tr("Play Camera Path"), QString(), tr("Camera paths (*.camera);;All files (*)"));
  if (!path.isEmpty())
  {
    PlayCameraPath(path);
  }
}

void ViewerWindow::closeEvent(QCloseEvent* event)
{
  ConvergenceTimer.stop();
  PlaybackTimer.stop();
  QMainWindow::closeEvent(event);
}

}
