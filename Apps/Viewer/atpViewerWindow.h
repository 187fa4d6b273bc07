// atp-view's main window, laid out like ParaView's: the render view in the middle, the
// properties and statistics panels docked at the left, File and Camera menus and a toolbar.
// It opens a .atp model (or builds one from a mesh or a volume first), keeps rendering while the mapper
// streams patches in, saves screenshots, and records and plays back camera paths.
//
// Errors a user can cause (a missing or corrupt model, a mesh that does not build, a bad
// camera path) show a message box and the status bar, and the window keeps what it showed.
#ifndef atpViewerWindow_h
#define atpViewerWindow_h

#include "atpCameraPath.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <QElapsedTimer>
#include <QMainWindow>
#include <QMessageBox>
#include <QTimer>

class QAction;
class QVTKOpenGLNativeWidget;
class vtkActor;
class vtkATPMapper;
class vtkATPReader;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

namespace atp
{
class ModelBuild;
class PropertiesPanel;
class StatisticsPanel;

class ViewerWindow : public QMainWindow
{
  Q_OBJECT

public:
  explicit ViewerWindow(QWidget* parent = nullptr);
  ~ViewerWindow() override;

  /// Opens a model, or a mesh (.ply, .obj, .stl, .vtp) or a volume (.nii, .nii.gz, .vti: its
  /// isosurface at `isoValue`) by building it into `model` first (default: the input's name
  /// with .atp, beside it).
  void OpenFile(const QString& path, const QString& model = QString(), double isoValue = 0);
  /// Shows the model at `path`; false (and an error shown) when it cannot be opened.
  bool OpenModel(const QString& path);
  /// Builds a mesh, or a volume's isosurface at `isoValue`, into `model` in the background
  /// with a progress dialog, then opens it.
  void BuildModel(const QString& input, const QString& model, double isoValue = 0);
  bool Building() const { return Build != nullptr; }
  /// Writes what the view shows as PNG; false (and an error shown) when it cannot.
  bool SaveScreenshot(const QString& path);

  /// Records the camera at every frame from now on.
  void StartRecording();
  /// Stops recording and writes the path; false (and an error shown) when it cannot.
  bool StopRecording(const QString& path);
  bool Recording() const { return IsRecording; }
  /// Flies the camera along a recorded path in real time; false (and an error shown) when
  /// the file is not a camera path.
  bool PlayCameraPath(const QString& path);
  bool Playing() const { return PlaybackTimer.isActive(); }

  /// A model is shown and its last frame drew the whole cut the view asks for.
  bool Converged() const;
  void Render();

  QVTKOpenGLNativeWidget* View() const { return RenderView; }
  vtkRenderer* Renderer() const { return SceneRenderer; }
  vtkATPMapper* Mapper() const { return ModelMapper; }
  PropertiesPanel* Properties() const { return PropertiesDock; }
  StatisticsPanel* Statistics() const { return StatisticsDock; }

signals:
  void ModelOpened(const QString& path);
  void PlaybackFinished();
  /// An error was shown to the user (the message box's text).
  void ErrorShown(const QString& message);
  /// A warning was shown to the user; the window goes on as before.
  void WarningShown(const QString& message);
  /// A patch turned out corrupt while drawing: shown in the status bar, its region left coarser.
  void PatchErrorShown(const QString& message);

protected:
  void closeEvent(QCloseEvent* event) override;

private:
  void CreateActions();
  void ShowError(const QString& title, const QString& message);
  /// A built model with something wrong in its input (vtkATPBuilder::GetWarningMessage).
  void ShowWarning(const QString& title, const QString& message);
  /// The status bar, and a message box that does not block: "errorMessage" or "warningMessage".
  void ShowMessageBox(QMessageBox::Icon icon, const char* name, const QString& title, const QString& message);
  void Rendered();
  void PlaybackStep();
  void ChooseModel();
  void ChooseInput();
  void ChooseScreenshot();
  void ToggleRecording(bool on);
  void ChooseCameraPath();
  void ResetCamera();

  QVTKOpenGLNativeWidget* RenderView;
  vtkNew<vtkGenericOpenGLRenderWindow> RenderWindow;
  vtkNew<vtkRenderer> SceneRenderer;
  vtkNew<vtkATPMapper> ModelMapper;
  vtkNew<vtkActor> Actor;
  vtkSmartPointer<vtkATPReader> Reader;
  PropertiesPanel* PropertiesDock;
  StatisticsPanel* StatisticsDock;
  ModelBuild* Build = nullptr;

  QAction* BuildAction = nullptr;
  QAction* RecordAction = nullptr;
  QTimer ConvergenceTimer; ///< renders again while patches stream in
  QTimer PlaybackTimer;
  QElapsedTimer Clock;     ///< since recording or playback started
  CameraPath Path;
  bool IsRecording = false;
  double LastIsoValue = 0;
};

}

#endif
