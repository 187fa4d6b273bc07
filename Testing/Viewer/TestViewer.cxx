// atp-view driven as a person would drive it: the main window on screen (xvfb-run), the
// panel's widgets clicked and typed into, the camera dragged and zoomed with mouse events on
// the VTK widget, screenshots compared with baselines through vtkTesting.
#include "RenderingFixture.h"
#include "TestModel.h"

#include "atpCameraPath.h"
#include "atpProgressReport.h"
#include "atpPropertiesPanel.h"
#include "atpRenderStatistics.h"
#include "atpStatisticsPanel.h"
#include "atpViewerWindow.h"
#include "vtkATPMapper.h"

#include "QVTKOpenGLNativeWidget.h"
#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLightCollection.h"
#include "vtkProperty.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkXMLImageDataWriter.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFile>
#include <QLabel>
#include <QMessageBox>
#include <QPointer>
#include <QProgressDialog>
#include <QPushButton>
#include <QSurfaceFormat>
#include <QTest>
#include <QTimer>
#include <QToolBar>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <cmath>
#include <fstream>
#include <random>
#include <unistd.h>

namespace
{
using namespace atp::test;

/// What vtkTesting accepts for one rendering path drawn twice (TestMapper's baseline
/// threshold: llvmpipe's rasterization may differ by a few edge pixels between runs).
constexpr double BaselineThreshold = 0.15;
constexpr int Width = 400, Height = 300;

void EnsureApplication()
{
  if (!QApplication::instance())
  {
    QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
    static int argc = 1;
    static char name[] = "TestViewer";
    static char* argv[] = { name, nullptr };
    new QApplication(argc, argv); // lives until the process ends, as an application's does
  }
}

/// The main window on screen with a render view of Width x Height.
struct Viewer
{
  Viewer()
  {
    EnsureApplication();
    Window.reset(new atp::ViewerWindow);
    Window->View()->setFixedSize(Width, Height);
    Window->show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(Window.get()));
  }

  atp::ViewerWindow* operator->() { return Window.get(); }

  bool WaitUntilConverged(int milliseconds = 30000)
  {
    return QTest::qWaitFor([this] { return Window->Converged(); }, milliseconds);
  }

  std::unique_ptr<atp::ViewerWindow> Window;
};

/// Drags on the render view from `from` to `to` with `button` held, in `steps` moves.
void Drag(QWidget* view, Qt::MouseButton button, QPoint from, QPoint to, int steps, int pauseMs = 0)
{
  QTest::mousePress(view, button, Qt::NoModifier, from);
  for (int i = 1; i <= steps; ++i)
  {
    const QPoint at = from + (to - from) * i / steps;
    // QTest::mouseMove does not carry the held button: the event is sent as Qt would.
    QMouseEvent move(QEvent::MouseMove, at, view->mapToGlobal(at), Qt::NoButton, button, Qt::NoModifier);
    QApplication::sendEvent(view, &move);
    if (pauseMs)
    {
      QTest::qWait(pauseMs);
    }
  }
  QTest::mouseRelease(view, button, Qt::NoModifier, to);
}

/// One notch of the mouse wheel forward (zoom in) over the render view's centre.
void WheelForward(QWidget* view)
{
  const QPoint at(view->width() / 2, view->height() / 2);
  QWheelEvent wheel(at, view->mapToGlobal(at), QPoint(), QPoint(0, 120), Qt::NoButton,
    Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(view, &wheel);
}

/// Clicks the main toolbar's button for the action named `name`.
void ClickToolButton(atp::ViewerWindow* window, const QString& name)
{
  auto* action = window->findChild<QAction*>(name);
  auto* toolbar = window->findChild<QToolBar*>("mainToolBar");
  ASSERT_TRUE(action && toolbar) << name.toStdString();
  QTest::mouseClick(toolbar->widgetForAction(action), Qt::LeftButton);
}

/// Answers the next file dialogs, in turn, with `paths` (they open modally, so this waits for
/// each from the dialog's own event loop).
void AnswerFileDialogs(const QStringList& paths)
{
  auto* poll = new QTimer;
  auto answered = std::make_shared<QPointer<QFileDialog>>();
  auto next = std::make_shared<int>(0);
  QObject::connect(poll, &QTimer::timeout, [=] {
    auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
    if (!dialog || dialog == *answered)
    {
      return;
    }
    *answered = dialog;
    dialog->selectFile(paths[(*next)++]);
    static_cast<QDialog*>(dialog)->accept(); // what its Save or Open button does
    if (*next == paths.size())
    {
      poll->stop();
      poll->deleteLater();
    }
  });
  poll->start(10);
}

/// Clicks a check box where its indicator is, as a person would.
void Click(QCheckBox* box)
{
  QTest::mouseClick(box, Qt::LeftButton, Qt::NoModifier, QPoint(6, box->height() / 2));
}

/// Types a new value into a spin box and confirms it with Enter.
void Type(QAbstractSpinBox* box, const QString& text)
{
  box->setFocus();
  box->selectAll();
  QTest::keyClicks(box, text);
  QTest::keyClick(box, Qt::Key_Enter);
}

std::array<double, 10> CameraOf(vtkRenderer* renderer)
{
  vtkCamera* c = renderer->GetActiveCamera();
  std::array<double, 10> v{};
  c->GetPosition(&v[0]);
  c->GetFocalPoint(&v[3]);
  c->GetViewUp(&v[6]);
  v[9] = c->GetViewAngle();
  return v;
}

double Distance(const std::array<double, 10>& a, const std::array<double, 10>& b)
{
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return std::sqrt(sum);
}

/// The error box the window shows, if any, with its text.
QMessageBox* ErrorBox(atp::ViewerWindow* window)
{
  return window->findChild<QMessageBox*>("errorMessage");
}

TEST(Viewer, OpensAModelAndShowsItsStatistics)
{
  Viewer viewer;
  ASSERT_TRUE(viewer->OpenModel(QString::fromStdString(TorusModel())));
  ASSERT_TRUE(viewer.WaitUntilConverged());
  const atp::RenderStatistics& stats = viewer->Mapper()->GetStatistics();
  EXPECT_GT(stats.Triangles, 0u);
  EXPECT_GT(stats.Patches, 0u);
  atp::StatisticsPanel* panel = viewer->Statistics();
  EXPECT_EQ(panel->Label("triangles")->text().toStdString(), atp::FormatCount(double(stats.Triangles)));
  EXPECT_EQ(panel->Label("patches")->text().toStdString(), atp::FormatCount(double(stats.Patches)));
  EXPECT_NE(panel->Label("triangles")->text(), "0");
  EXPECT_TRUE(panel->Label("frameRate")->text().endsWith("ms)")) << panel->Label("frameRate")->text().toStdString();
  EXPECT_TRUE(panel->Label("memory")->text().endsWith("MiB"));
  EXPECT_TRUE(panel->Label("gpuCache")->text().contains(" MiB buffer), "))
    << panel->Label("gpuCache")->text().toStdString();
  EXPECT_EQ(panel->Label("converged")->text(), "yes");
  EXPECT_EQ(ErrorBox(viewer.Window.get()), nullptr);

  // A screenshot that cannot be written is an error box, not a crash.
  EXPECT_FALSE(viewer->SaveScreenshot("/nonexistent/directory/shot.png"));
  ASSERT_NE(ErrorBox(viewer.Window.get()), nullptr);
  EXPECT_TRUE(ErrorBox(viewer.Window.get())->text().contains("/nonexistent/directory/shot.png"))
    << ErrorBox(viewer.Window.get())->text().toStdString();
}

TEST(Viewer, PropertiesAndTrackballMatchTheBaseline)
{
  Viewer viewer;
  ASSERT_TRUE(viewer->OpenModel(QString::fromStdString(TorusModel())));
  ASSERT_TRUE(viewer.WaitUntilConverged());
  const std::uint64_t trianglesAtOnePixel = viewer->Mapper()->GetStatistics().Triangles;

  Type(viewer->Properties()->TolerancePixels(), "3");
  EXPECT_EQ(viewer->Mapper()->GetTolerancePixels(), 3.0);
  Click(viewer->Properties()->PatchColoring());
  EXPECT_TRUE(viewer->Mapper()->GetPatchColoring());

  // Rotate a quarter of the view's width to the right and down a little, then zoom in.
  const auto before = CameraOf(viewer->Renderer());
  QWidget* view = viewer->View();
  Drag(view, Qt::LeftButton, QPoint(200, 150), QPoint(300, 190), 10);
  WheelForward(view);
  WheelForward(view);
  EXPECT_GT(Distance(before, CameraOf(viewer->Renderer())), 0.1) << "the camera did not move";
  ASSERT_TRUE(viewer.WaitUntilConverged());
  EXPECT_LT(viewer->Mapper()->GetStatistics().Triangles, trianglesAtOnePixel)
    << "a coarser tolerance must draw fewer triangles";

  const std::string screenshot = TempPath("viewer.png");
  AnswerFileDialogs({ QString::fromStdString(screenshot) });
  ClickToolButton(viewer.Window.get(), "saveScreenshot");
  double error = 0;
  EXPECT_TRUE(MatchesBaseline(screenshot, "ATPViewerTrackball", BaselineThreshold, error))
    << "image error " << error;

  // The comparison sees the difference one property makes.
  Click(viewer->Properties()->PatchColoring());
  ASSERT_TRUE(viewer.WaitUntilConverged());
  ASSERT_TRUE(viewer->SaveScreenshot(QString::fromStdString(screenshot)));
  EXPECT_FALSE(MatchesBaseline(screenshot, "ATPViewerTrackball", BaselineThreshold, error))
    << "without patch colors: image error " << error;
  ::unlink(screenshot.c_str());
}

TEST(Viewer, EveryPropertyReachesTheMapperActorOrRenderer)
{
  Viewer viewer;
  ASSERT_TRUE(viewer->OpenModel(QString::fromStdString(TorusModel())));
  atp::PropertiesPanel* panel = viewer->Properties();
  Type(panel->CacheBudgetMiB(), "64");
  EXPECT_EQ(viewer->Mapper()->GetCacheBudget(), vtkTypeInt64(64) << 20);
  Click(panel->Prefetching());
  EXPECT_FALSE(viewer->Mapper()->GetPrefetching());
  Click(panel->BackfaceCulling());
  EXPECT_TRUE(viewer->Mapper()->GetBackfaceCulling());

  vtkActor* actor = viewer->Renderer()->GetActors()->GetLastActor();
  ASSERT_NE(actor, nullptr);
  auto* representation = panel->findChild<QComboBox*>("representation");
  ASSERT_NE(representation, nullptr);
  representation->setFocus();
  QTest::keyClick(representation, Qt::Key_Up); // Surface -> Wireframe
  EXPECT_EQ(actor->GetProperty()->GetRepresentation(), VTK_WIREFRAME);
  for (const char* name : { "ambient", "diffuse", "specular" })
  {
    Type(panel->findChild<QDoubleSpinBox*>(name), "0.25");
  }
  Type(panel->findChild<QDoubleSpinBox*>("specularPower"), "40");
  EXPECT_EQ(actor->GetProperty()->GetAmbient(), 0.25);
  EXPECT_EQ(actor->GetProperty()->GetDiffuse(), 0.25);
  EXPECT_EQ(actor->GetProperty()->GetSpecular(), 0.25);
  EXPECT_EQ(actor->GetProperty()->GetSpecularPower(), 40);

  Click(panel->LightKit());
  EXPECT_GE(viewer->Renderer()->GetLights()->GetNumberOfItems(), 4) << "a light kit has 4 lights";
  Click(panel->LightKit());
  viewer->Render(); // the renderer makes its headlight again
  EXPECT_EQ(viewer->Renderer()->GetLights()->GetNumberOfItems(), 1);

  // Drawn with all of it, the view still converges and draws triangles.
  ASSERT_TRUE(viewer.WaitUntilConverged());
  EXPECT_GT(viewer->Mapper()->GetStatistics().Triangles, 0u);
}

TEST(Viewer, ACorruptModelShowsAnErrorAndTheViewerKeepsWorking)
{
  Viewer viewer;
  const QString good = QString::fromStdString(TorusModel());
  ASSERT_TRUE(viewer->OpenModel(good));
  ASSERT_TRUE(viewer.WaitUntilConverged());

  // The model with its node section damaged: the reader's checksum catches it.
  const std::string corrupt = TempPath("corrupt.atp");
  {
    std::ifstream in(TorusModel(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::size_t i = 200; i < 400 && i < bytes.size(); ++i)
    {
      bytes[i] = char(~bytes[i]);
    }
    std::ofstream(corrupt, std::ios::binary) << bytes;
  }
  for (const std::string& bad : { corrupt, TempPath("missing.atp") })
  {
    EXPECT_FALSE(viewer->OpenModel(QString::fromStdString(bad)));
    QMessageBox* box = ErrorBox(viewer.Window.get());
    ASSERT_NE(box, nullptr);
    EXPECT_TRUE(box->isVisible());
    EXPECT_TRUE(box->text().contains(QString::fromStdString(bad))) << box->text().toStdString();
    QTest::keyClick(box, Qt::Key_Enter); // a person reads it and presses OK
    EXPECT_TRUE(QTest::qWaitFor([&] { return !ErrorBox(viewer.Window.get()); }));
  }
  ::unlink(corrupt.c_str());

  // The model shown before is still shown and still answers the mouse.
  Drag(viewer->View(), Qt::LeftButton, QPoint(200, 150), QPoint(120, 150), 5);
  ASSERT_TRUE(viewer.WaitUntilConverged());
  EXPECT_GT(viewer->Mapper()->GetStatistics().Triangles, 0u);
  EXPECT_TRUE(viewer->OpenModel(good));
}

TEST(Viewer, ARecordedCameraPathPlaysBackToTheRecordedCamera)
{
  Viewer viewer;
  Type(viewer->Properties()->TolerancePixels(), "8"); // fewer triangles: quicker frames
  ASSERT_TRUE(viewer->OpenModel(QString::fromStdString(TorusModel())));
  ASSERT_TRUE(viewer.WaitUntilConverged());

  ClickToolButton(viewer.Window.get(), "recordCameraPath");
  ASSERT_TRUE(viewer->Recording());
  QWidget* view = viewer->View();
  Drag(view, Qt::LeftButton, QPoint(200, 150), QPoint(260, 100), 5, 20);
  QTest::qWait(100); // a pause, kept in the path
  WheelForward(view);
  Drag(view, Qt::LeftButton, QPoint(200, 150), QPoint(150, 150), 5, 20);
  const auto recorded = CameraOf(viewer->Renderer());
  const std::string path = TempPath("flight.camera");
  AnswerFileDialogs({ QString::fromStdString(path) }); // where to save it
  ClickToolButton(viewer.Window.get(), "recordCameraPath");
  ASSERT_FALSE(viewer->Recording());
  const atp::CameraPath flight = atp::CameraPath::Load(path);
  EXPECT_GT(flight.Keyframes().size(), 8u);
  EXPECT_GT(flight.Duration(), 0.2);

  // Elsewhere, then back along the path.
  Drag(view, Qt::LeftButton, QPoint(100, 100), QPoint(300, 250), 5);
  ASSERT_GT(Distance(recorded, CameraOf(viewer->Renderer())), 0.1);
  AnswerFileDialogs({ QString::fromStdString(path) }); // which path to play
  ClickToolButton(viewer.Window.get(), "playCameraPath");
  EXPECT_TRUE(viewer->Playing());
  ASSERT_TRUE(QTest::qWaitFor([&] { return !viewer->Playing(); }, 20000));
  EXPECT_LT(Distance(recorded, CameraOf(viewer->Renderer())), 1e-9);
  ::unlink(path.c_str());

  // A file that is not a camera path: an error naming the line, nothing played.
  const std::string bad = TempPath("bad.camera");
  std::ofstream(bad) << "# a path\n0 0 0 1 0 0 0 0 1 0 30\n1 2 3\n";
  EXPECT_FALSE(viewer->PlayCameraPath(QString::fromStdString(bad)));
  ASSERT_NE(ErrorBox(viewer.Window.get()), nullptr);
  EXPECT_TRUE(ErrorBox(viewer.Window.get())->text().contains(QString::fromStdString(bad) + ":3:"));
  EXPECT_FALSE(viewer->Playing());
  ::unlink(bad.c_str());
}

TEST(Viewer, BuildsAModelFromAMeshBehindAProgressDialog)
{
  Viewer viewer;
  const std::string model = TempPath("built.atp");
  AnswerFileDialogs({ ATP_DATA_DIR "/bumpy-torus.ply", QString::fromStdString(model) });
  ClickToolButton(viewer.Window.get(), "buildModel"); // the mesh, then where its model goes
  QPointer<QProgressDialog> progress = viewer->findChild<QProgressDialog*>("buildProgress");
  ASSERT_NE(progress, nullptr);
  EXPECT_TRUE(progress->isVisible());
  EXPECT_TRUE(viewer->Building());
  int shown = 0; // the most progress the dialog showed (of 1000)
  ASSERT_TRUE(QTest::qWaitFor([&] {
    shown = progress ? std::max(shown, progress->value()) : shown;
    return !viewer->Building();
  }, 120000));
  EXPECT_GT(shown, 0) << "the dialog never showed the builder's progress";
  EXPECT_EQ(ErrorBox(viewer.Window.get()), nullptr);
  ASSERT_TRUE(viewer.WaitUntilConverged());
  EXPECT_TRUE(viewer->windowTitle().startsWith("atp-test-")) << viewer->windowTitle().toStdString();
  EXPECT_GT(viewer->Mapper()->GetStatistics().Triangles, 0u);
  EXPECT_EQ(::unlink(model.c_str()), 0) << "the model was not written";
}

TEST(Viewer, ABuildCanBeCancelledAndABadMeshIsAnError)
{
  Viewer viewer;
  const std::string model = TempPath("cancelled.atp");
  viewer->BuildModel(ATP_DATA_DIR "/bumpy-torus.ply", QString::fromStdString(model));
  auto* progress = viewer->findChild<QProgressDialog*>("buildProgress");
  ASSERT_NE(progress, nullptr);
  auto* cancel = progress->findChild<QPushButton*>();
  ASSERT_NE(cancel, nullptr);
  QTest::mouseClick(cancel, Qt::LeftButton);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !viewer->Building(); }, 60000));
  EXPECT_EQ(ErrorBox(viewer.Window.get()), nullptr) << "cancelling is not an error";
  EXPECT_NE(::access(model.c_str(), F_OK), 0) << "a cancelled build left a model";
  EXPECT_FALSE(viewer->Converged()) << "nothing to show";

  const std::string mesh = TempPath("broken.ply");
  std::ofstream(mesh) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2\n";
  viewer->BuildModel(QString::fromStdString(mesh), QString::fromStdString(model));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !viewer->Building(); }, 60000));
  QMessageBox* box = ErrorBox(viewer.Window.get());
  ASSERT_NE(box, nullptr);
  EXPECT_TRUE(box->text().contains("broken.ply")) << box->text().toStdString();
  EXPECT_NE(::access(model.c_str(), F_OK), 0);
  ::unlink(mesh.c_str());
}

// A mesh whose triangles are wound either way at random builds, and the window says what is
// wrong with it.
TEST(Viewer, ABuildWithAWarningShowsIt)
{
  const std::string mesh = TempPath("turned.obj");
  {
    std::ofstream obj(mesh);
    const int nu = 160, nv = 80; // several leaves at the default capacity, so diamonds above them
    for (int j = 0; j < nv; ++j)
    {
      for (int i = 0; i < nu; ++i)
      {
        const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
        obj << "v " << (1 + 0.4 * std::cos(v)) * std::cos(u) << ' ' << (1 + 0.4 * std::cos(v)) * std::sin(u)
            << ' ' << 0.4 * std::sin(v) << '\n';
      }
    }
    std::mt19937 random(7);
    const auto corner = [&](int i, int j) { return (j % nv) * nu + i % nu + 1; };
    for (int j = 0; j < nv; ++j)
    {
      for (int i = 0; i < nu; ++i)
      {
        for (const std::array<int, 3> t : { std::array<int, 3>{ corner(i, j), corner(i + 1, j), corner(i + 1, j + 1) },
               std::array<int, 3>{ corner(i, j), corner(i + 1, j + 1), corner(i, j + 1) } })
        {
          const bool turn = random() % 2 == 1;
          obj << "f " << t[0] << ' ' << t[turn ? 2 : 1] << ' ' << t[turn ? 1 : 2] << '\n';
        }
      }
    }
  }
  Viewer viewer;
  const std::string model = TempPath("turned.atp");
  viewer->BuildModel(QString::fromStdString(mesh), QString::fromStdString(model));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !viewer->Building(); }, 120000));
  EXPECT_EQ(ErrorBox(viewer.Window.get()), nullptr);
  auto* box = viewer->findChild<QMessageBox*>("warningMessage");
  ASSERT_NE(box, nullptr) << "no warning shown";
  EXPECT_TRUE(box->text().contains("wound either way")) << box->text().toStdString();
  ASSERT_TRUE(viewer.WaitUntilConverged()) << "the model opens all the same";
  ::unlink(mesh.c_str());
  ::unlink(model.c_str());
}

/// A distance field around the centre of a 24^3 grid, as VTK image data: its isosurface at 8
/// is a sphere of radius 8.
std::string SphereVolume()
{
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(24, 24, 24);
  volume->AllocateScalars(VTK_FLOAT, 1);
  auto* values = static_cast<float*>(volume->GetScalarPointer());
  for (int z = 0; z < 24; ++z)
  {
    for (int y = 0; y < 24; ++y)
    {
      for (int x = 0; x < 24; ++x)
      {
        *values++ = float(std::sqrt((x - 11.5) * (x - 11.5) + (y - 11.5) * (y - 11.5) + (z - 11.5) * (z - 11.5)));
      }
    }
  }
  const std::string path = TempPath("sphere.vti");
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(path.c_str());
  EXPECT_EQ(writer->Write(), 1);
  return path;
}

TEST(Viewer, BuildsAModelFromAVolumesIsosurface)
{
  Viewer viewer;
  const std::string volume = SphereVolume();
  const std::string model = TempPath("sphere.atp");
  viewer->BuildModel(QString::fromStdString(volume), QString::fromStdString(model), 8);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !viewer->Building(); }, 60000));
  EXPECT_EQ(ErrorBox(viewer.Window.get()), nullptr);
  ASSERT_TRUE(viewer.WaitUntilConverged());
  EXPECT_GT(viewer->Mapper()->GetStatistics().Triangles, 500u);
  const double* bounds = viewer->Mapper()->GetBounds();
  for (int axis = 0; axis < 3; ++axis)
  {
    EXPECT_NEAR(bounds[2 * axis], 11.5 - 8, 0.1);
    EXPECT_NEAR(bounds[2 * axis + 1], 11.5 + 8, 0.1);
  }
  ::unlink(model.c_str());

  // Not a volume: the error names the file.
  std::ofstream(volume) << "not XML at all\n";
  viewer->BuildModel(QString::fromStdString(volume), QString::fromStdString(model), 8);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !viewer->Building(); }, 60000));
  QMessageBox* box = ErrorBox(viewer.Window.get());
  ASSERT_NE(box, nullptr);
  EXPECT_TRUE(box->text().contains("sphere.vti")) << box->text().toStdString();
  EXPECT_NE(::access(model.c_str(), F_OK), 0);
  ::unlink(volume.c_str());
}

TEST(CameraPath, SavesAndLoadsExactlyAndInterpolates)
{
  atp::CameraPath path;
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.1, 0.2, 3.3);
  path.Record(0, camera);
  camera->SetPosition(1.0 / 3, 0.2, 5.3);
  camera->SetViewAngle(40);
  path.Record(2, camera);
  const std::string file = TempPath("exact.camera");
  path.Save(file);
  const atp::CameraPath loaded = atp::CameraPath::Load(file);
  ::unlink(file.c_str());
  ASSERT_EQ(loaded.Keyframes().size(), 2u);
  EXPECT_EQ(loaded.Keyframes()[1].Position[0], 1.0 / 3);
  EXPECT_EQ(loaded.Keyframes()[1].ViewAngle, 40);

  loaded.Apply(1, camera);
  EXPECT_NEAR(camera->GetPosition()[2], 4.3, 1e-12);
  EXPECT_NEAR(camera->GetViewAngle(), 35, 1e-12);
  loaded.Apply(99, camera);
  EXPECT_EQ(camera->GetPosition()[0], 1.0 / 3);

  // A hand-written path that starts late plays from its first keyframe (it waited for it).
  std::ofstream(file) << "1000000000 0 0 7 0 0 0 0 1 0 30\n1000000001 0 0 9 0 0 0 0 1 0 30\n";
  const atp::CameraPath late = atp::CameraPath::Load(file);
  ::unlink(file.c_str());
  EXPECT_EQ(late.Keyframes().front().Time, 0);
  EXPECT_EQ(late.Duration(), 1);
}

TEST(CameraPath, NamesTheLineOfAMistake)
{
  const std::string file = TempPath("mistakes.camera");
  const char* const bad[] = {
    "0 0 0 1 0 0 0 0 1 0 30\n0 0 0 2 0 0 0 0 1 0 30\n", // time not increasing
    "0 0 0 1 0 0 0 0 1 0 30\n1 0 0 1 0 0 0 0 1 0 30 7\n", // a twelfth number
    "\n# comment\n0 0 0 1 0 0 0 0 1 0 nan\n",             // not finite
    "0 0 0 1 0 0 1 0 1 0 30\n",                           // eye at the focal point
    "0 0 0 1 0 0 0 0 1 0 30\n1 0 0 1 0 0 0 0 0 2 30\n",    // view up along the view
    "0 1e300 0 1 0 0 0 0 1 0 30\n",                        // beyond what a camera squares
    "0 0 0 1 0 0 0 0 1 0 30\n100000 0 0 2 0 0 0 0 1 0 30\n", // longer than a day
    "# nothing\n",
  };
  const char* const where[] = { ":2:", ":2:", ":3:", ":1:", ":2: the view up", ":1: coordinates", "more than a day",
    "no keyframes" };
  for (std::size_t i = 0; i < std::size(bad); ++i)
  {
    std::ofstream(file) << bad[i];
    try
    {
      atp::CameraPath::Load(file);
      ADD_FAILURE() << "accepted: " << bad[i];
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(std::string(e.what()).find(where[i]), std::string::npos) << e.what();
    }
  }
  ::unlink(file.c_str());
}

} // namespace
