// vtkATPMapper in VTK's image-comparison harness: fidelity against vtkPolyDataMapper on the
// full-resolution input, baselines, a test that the comparison can fail, small caches,
// corrupt patches, several renderers and windows, and frames that never wait for decoding.
#include "MeshEdges.h"
#include "RenderingFixture.h"

#include "atpCut.h"
#include "atpModelFile.h"
#include "atpRenderStatistics.h"
#include "atpTetra.h"
#include "atpWindowImage.h"
#include "vtkATPBuilder.h"
#include "vtkATPMapper.h"
#include "vtkATPReader.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPLYReader.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <unistd.h>

namespace
{
using namespace atp::test;

/// VTK's regression tests accept an image error up to this (vtkRegressionTestImage's 0.05 is
/// for identical code paths; two mappers and two triangulations get a little more).
constexpr double FidelityThreshold = 0.15;
constexpr int Width = 400, Height = 300;

vtkRenderer* FirstRenderer(vtkRenderWindow* window)
{
  return window->GetRenderers()->GetFirstRenderer();
}

struct AtpScene
{
  vtkNew<vtkATPReader> Reader;
  vtkNew<vtkATPMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkSmartPointer<vtkRenderWindow> Window = MakeWindow(Width, Height);

  explicit AtpScene(const std::string& model = TorusModel())
  {
    Reader->SetFileName(model.c_str());
    Mapper->SetInputConnection(Reader->GetOutputPort());
    Actor->SetMapper(Mapper);
    FirstRenderer(Window)->AddActor(Actor);
  }
};

/// An AtpScene whose window shows the model in two views side by side, each with its camera,
/// at a few patches uploaded per frame, so that a view takes several frames to converge.
struct TwoViewScene : AtpScene
{
  vtkRenderer* Left = FirstRenderer(Window);
  vtkNew<vtkRenderer> Right;

  TwoViewScene()
  {
    Mapper->SetUploadBudget(64 << 10);
    Left->SetViewport(0, 0, 0.5, 1);
    Right->SetViewport(0.5, 0, 1, 1);
    Right->AddActor(Actor);
    Window->AddRenderer(Right);
  }
};

/// How a comparison poses the actor (before the camera is aimed) and the camera (after), the
/// same in both of its scenes.
struct Pose
{
  std::function<void(vtkActor*)> Actor = [](vtkActor*) {};
  std::function<void(vtkCamera*)> Camera = [](vtkCamera*) {};
};

/// The input mesh at full resolution, drawn by VTK's own mapper, with smooth normals.
vtkSmartPointer<vtkImageData> FullResolution(double azimuth, double elevation, double zoom, const Pose& pose = {})
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(ATP_DATA_DIR "/bumpy-torus.ply");
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(reader->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  auto window = MakeWindow(Width, Height);
  FirstRenderer(window)->AddActor(actor);
  pose.Actor(actor);
  AimCamera(FirstRenderer(window), azimuth, elevation, zoom);
  pose.Camera(FirstRenderer(window)->GetActiveCamera());
  window->Render();
  return atp::CaptureWindow(window);
}

TEST(Mapper, MatchesTheFullResolutionMapperAtOnePixel)
{
  struct View
  {
    double Azimuth, Elevation, Zoom;
  };
  for (const View v : { View{ 30, 40, 1.0 }, View{ 150, -20, 1.6 }, View{ 260, 70, 3.0 } })
  {
    AtpScene scene;
    AimCamera(FirstRenderer(scene.Window), v.Azimuth, v.Elevation, v.Zoom);
    EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
    const atp::RenderStatistics& stats = scene.Mapper->GetStatistics();
    EXPECT_GT(stats.Triangles, 0u);
    const double error = ImageError(FullResolution(v.Azimuth, v.Elevation, v.Zoom), atp::CaptureWindow(scene.Window));
    std::printf("view %g/%g/%g: %zu patches, %llu triangles, image error %.4f\n", v.Azimuth,
      v.Elevation, v.Zoom, stats.Patches, static_cast<unsigned long long>(stats.Triangles), error);
    EXPECT_LE(error, FidelityThreshold)
      << "view " << v.Azimuth << "/" << v.Elevation << "/" << v.Zoom << ": " << stats.Patches
      << " patches, " << stats.Triangles << " triangles";
  }
}

TEST(Mapper, MatchesTheFullResolutionMapperUnderUnevenStretchesAndOrthographicViews)
{
  // The cut measured errors and distances in the model's units: squashed along z and seen
  // along z, the torus stopped at its coarse levels (at a tenth, image error 55 against about
  // 0.03), and an explicit orthographic projection was taken for a perspective one.
  const auto orthographic = [](vtkCamera* camera) {
    const double* range = camera->GetClippingRange();
    const double halfHeight = camera->GetParallelScale(), aspect = double(Width) / Height;
    vtkNew<vtkMatrix4x4> projection;
    projection->SetElement(0, 0, 1 / (halfHeight * aspect));
    projection->SetElement(1, 1, 1 / halfHeight);
    projection->SetElement(2, 2, -2 / (range[1] - range[0]));
    projection->SetElement(2, 3, -(range[1] + range[0]) / (range[1] - range[0]));
    camera->SetExplicitProjectionTransformMatrix(projection);
    camera->UseExplicitProjectionTransformMatrixOn();
  };
  struct Case
  {
    const char* Name;
    double Azimuth, Elevation, Zoom;
    Pose Posed;
  };
  const Case cases[] = {
    { "squashed to a fifth along z, seen along z", 0, 0, 2.0, { [](vtkActor* a) { a->SetScale(1, 1, 0.2); } } },
    { "stretched and sheared, seen at a slant", 30, 40, 1.0, { [](vtkActor* a) {
        vtkNew<vtkMatrix4x4> shear;
        shear->SetElement(0, 1, 0.8);
        shear->SetElement(1, 1, 5);
        shear->SetElement(2, 2, 0.2);
        a->SetUserMatrix(shear);
      } } },
    { "squashed, parallel projection", 30, 40, 1.0,
      { [](vtkActor* a) { a->SetScale(1, 5, 0.2); }, [](vtkCamera* c) { c->ParallelProjectionOn(); } } },
    { "explicit orthographic projection", 30, 40, 1.0, { [](vtkActor*) {}, orthographic } },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.Name);
    AtpScene scene;
    c.Posed.Actor(scene.Actor);
    AimCamera(FirstRenderer(scene.Window), c.Azimuth, c.Elevation, c.Zoom);
    c.Posed.Camera(FirstRenderer(scene.Window)->GetActiveCamera());
    EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
    const double error = ImageError(
      FullResolution(c.Azimuth, c.Elevation, c.Zoom, c.Posed), atp::CaptureWindow(scene.Window));
    std::printf("%s: %llu triangles, image error %.4f\n", c.Name,
      static_cast<unsigned long long>(scene.Mapper->GetStatistics().Triangles), error);
    EXPECT_LE(error, FidelityThreshold);
  }
}

TEST(Mapper, ACoarseToleranceFailsTheSameComparison)
{
  AtpScene scene;
  scene.Mapper->SetTolerancePixels(60);
  AimCamera(FirstRenderer(scene.Window), 30, 40, 1.0);
  RenderUntilConverged(scene.Window, scene.Mapper);
  EXPECT_GT(ImageError(FullResolution(30, 40, 1.0), atp::CaptureWindow(scene.Window)), FidelityThreshold)
    << scene.Mapper->GetStatistics().Triangles << " triangles";
}

TEST(Mapper, Baselines)
{
  struct Case
  {
    const char* Name;
    double Azimuth, Elevation, Zoom;
    bool PatchColoring;
  };
  for (const Case c : { Case{ "ATPMapperOverview", 30, 40, 1.0, false },
         Case{ "ATPMapperPatchColoring", 30, 40, 1.0, true },
         Case{ "ATPMapperCloseUp", 100, 50, 2.5, false } })
  {
    AtpScene scene;
    scene.Mapper->SetPatchColoring(c.PatchColoring);
    AimCamera(FirstRenderer(scene.Window), c.Azimuth, c.Elevation, c.Zoom);
    RenderUntilConverged(scene.Window, scene.Mapper);
    double error = 0;
    EXPECT_TRUE(MatchesBaseline(scene.Window, c.Name, FidelityThreshold, error))
      << c.Name << ": image error " << error;
  }
}

TEST(Mapper, FramesNeverWaitForDecoding)
{
  AtpScene scene;
  scene.Mapper->SetUploadBudget(64 << 10); // a few patches per frame
  AimCamera(FirstRenderer(scene.Window), 30, 40, 2.0);
  scene.Window->Render();
  // The first frame draws what it has: the roots, decoded on the spot.
  EXPECT_FALSE(scene.Mapper->GetConverged());
  EXPECT_LE(scene.Mapper->GetStatistics().Patches, std::size_t(atp::RootCount));
  const int frames = RenderUntilConverged(scene.Window, scene.Mapper, 2000);
  EXPECT_GT(frames, 3);
  EXPECT_LE(frames, 2000);
  EXPECT_GT(scene.Mapper->GetStatistics().Patches, std::size_t(atp::RootCount));
}

TEST(Mapper, AFrameThatCullsTheModelIsConvergedWithNothingDrawn)
{
  // VTK does not call Render for an actor it culls: the figures of the last frame that drew
  // stood for such frames, and a render-until-converged loop never ended.
  AtpScene scene;
  scene.Mapper->SetUploadBudget(64 << 10); // a few patches per frame: not converged after one
  vtkRenderer* renderer = FirstRenderer(scene.Window);
  AimCamera(renderer, 30, 40, 2.0);
  scene.Window->Render();
  ASSERT_FALSE(scene.Mapper->GetConverged());
  const std::uint64_t frames = scene.Mapper->GetStatistics().Frame;
  renderer->GetActiveCamera()->Yaw(180); // the model behind the viewer
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetStatistics().Frame, frames) << "VTK drew the actor: nothing tested";
  EXPECT_TRUE(scene.Mapper->GetConverged());
  EXPECT_TRUE(scene.Mapper->GetDrawnNodes().empty());
  EXPECT_EQ(scene.Mapper->GetStatistics().Patches, 0u);
  renderer->GetActiveCamera()->Yaw(180);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper, 2000), 2000);
  EXPECT_GT(scene.Mapper->GetStatistics().Patches, std::size_t(atp::RootCount));
  EXPECT_FALSE(scene.Mapper->GetDrawnNodes().empty());
}

TEST(Mapper, ARendererThatCullsTheModelLeavesAnotherOnesCutComing)
{
  // Two views of one window, the right one looking away: the left one's cut is what counts.
  TwoViewScene scene;
  AimCamera(scene.Left, 30, 40, 2.0);
  AimCamera(scene.Right, 30, 40, 2.0);
  scene.Window->Render();
  scene.Right->GetActiveCamera()->Yaw(180);
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetConverged()) << "the left view's cut is still coming";
  EXPECT_FALSE(scene.Mapper->GetDrawnNodes().empty());
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper, 2000), 2000);
  EXPECT_GT(scene.Mapper->GetStatistics().Patches, std::size_t(atp::RootCount));
  // Both looking away: nothing drawn, nothing coming.
  scene.Left->GetActiveCamera()->Yaw(180);
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetConverged());
  EXPECT_TRUE(scene.Mapper->GetDrawnNodes().empty());
  EXPECT_EQ(scene.Mapper->GetStatistics().Patches, 0u);
}

TEST(Mapper, TwoViewsConvergeTogether)
{
  // A window of two views, a close one and a far one: converged said only whether the last
  // view drawn was, and a render-until-converged loop ended while the close one was coarse.
  TwoViewScene scene;
  AimCamera(scene.Left, 100, 50, 3.0); // close
  AimCamera(scene.Right, 30, 40, 0.3); // far
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper, 2000), 2000);
  const vtkSmartPointer<vtkImageData> converged = atp::CaptureWindow(scene.Window);
  for (int frame = 0; frame < 30; ++frame)
  {
    scene.Window->Render();
  }
  EXPECT_EQ(ImageError(converged, atp::CaptureWindow(scene.Window)), 0) << "the picture changed after it converged";
}

/// The nodes drawn in a view that culls nothing must form a crack-free surface.
void ExpectCrackFree(const std::vector<unsigned>& drawn)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  const std::vector<std::uint32_t> nodes(drawn.begin(), drawn.end());
  const atp::PatchMesh finest = atp::ExtractCut(model, atp::SelectLevel(model, 64));
  std::set<Position> boundary;
  for (const Edge& e : OpenEdges(finest))
  {
    boundary.insert(e.first);
    boundary.insert(e.second);
  }
  for (const Edge& e : OpenEdges(atp::ExtractCut(model, nodes)))
  {
    EXPECT_TRUE(boundary.count(e.first) && boundary.count(e.second)) << "a crack";
  }
}

TEST(Mapper, ATinyCacheStillDrawsAConformingCutAndSettles)
{
  AtpScene scene;
  scene.Mapper->SetCacheBudget(256 << 10);
  vtkRenderer* renderer = FirstRenderer(scene.Window);
  for (const double azimuth : { 0.0, 90.0, 180.0, 270.0 })
  {
    AimCamera(renderer, azimuth, 20, 0.9); // the whole torus in view: nothing culled
    // The cut does not fit: the picture settles coarser instead of trading patches forever.
    EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper, 400), 400);
    const atp::RenderStatistics& stats = scene.Mapper->GetStatistics();
    EXPECT_GT(stats.Patches, 0u);
    EXPECT_LE(stats.CacheBytes, std::uint64_t(256 << 10) + (1u << 20)) << "roots may exceed";
    ExpectCrackFree(scene.Mapper->GetDrawnNodes());
    const std::vector<unsigned> settled = scene.Mapper->GetDrawnNodes();
    for (int frame = 0; frame < 3; ++frame)
    {
      scene.Window->Render();
      EXPECT_EQ(scene.Mapper->GetDrawnNodes(), settled) << "a still camera's picture changed";
      EXPECT_EQ(scene.Mapper->GetStatistics().Uploads, 0u);
    }
  }
  EXPECT_GT(scene.Mapper->GetStatistics().Evictions, 0u);
}

TEST(Mapper, TheCacheBufferGrowsWithTheCutAndShrinksWithTheBudget)
{
  AtpScene scene;
  AimCamera(FirstRenderer(scene.Window), 30, 40, 1.0);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  const atp::RenderStatistics& grown = scene.Mapper->GetStatistics();
  // The buffer starts at 1 MiB: it grew, copying what it held, and the picture still matches.
  EXPECT_GT(grown.CacheBufferBytes, std::uint64_t(1) << 20);
  EXPECT_GE(grown.CacheBufferBytes, grown.CacheBytes);
  EXPECT_LE(ImageError(FullResolution(30, 40, 1.0), atp::CaptureWindow(scene.Window)), FidelityThreshold);
  // A smaller budget gives the GPU memory back: the next frames fill a buffer within it.
  scene.Mapper->SetCacheBudget(512 << 10);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper, 400), 400);
  const atp::RenderStatistics& shrunk = scene.Mapper->GetStatistics();
  EXPECT_GT(shrunk.Patches, 0u);
  EXPECT_LE(shrunk.CacheBufferBytes, std::uint64_t(512 << 10) + (1u << 20)) << "roots may exceed";
  ExpectCrackFree(scene.Mapper->GetDrawnNodes());
}

// Patches that did not fit wait for the view to change; more room must bring them back too.
TEST(Mapper, ARaisedBudgetRefinesAStillViewAgain)
{
  AtpScene scene;
  AimCamera(FirstRenderer(scene.Window), 30, 40, 1.0);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  const std::uint64_t full = scene.Mapper->GetStatistics().Patches;
  scene.Mapper->SetCacheBudget(100 << 10);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  EXPECT_LT(scene.Mapper->GetStatistics().Patches, full);
  scene.Mapper->SetCacheBudget(vtkTypeInt64(512) << 20);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  EXPECT_EQ(scene.Mapper->GetStatistics().Patches, full);
  EXPECT_LE(ImageError(FullResolution(30, 40, 1.0), atp::CaptureWindow(scene.Window)), FidelityThreshold);
}

// Its shader has no normals: the layout must not ask for them (VTK logs an error each time).
TEST(Mapper, AnUnlitActorDrawsWithoutErrors)
{
  AtpScene scene;
  scene.Actor->GetProperty()->LightingOff();
  int errors = 0;
  vtkNew<vtkCallbackCommand> count;
  count->SetClientData(&errors);
  count->SetCallback([](vtkObject*, unsigned long, void* counter, void*) { ++*static_cast<int*>(counter); });
  vtkOutputWindow* output = vtkOutputWindow::GetInstance();
  const unsigned long tag = output->AddObserver(vtkCommand::ErrorEvent, count);
  AimCamera(FirstRenderer(scene.Window), 30, 40, 1.0);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  output->RemoveObserver(tag);
  EXPECT_EQ(errors, 0);
  EXPECT_GT(scene.Mapper->GetStatistics().Patches, 6u);
}

TEST(Mapper, CachedPatchesCostNoUploads)
{
  AtpScene scene;
  AimCamera(FirstRenderer(scene.Window), 30, 40, 1.0);
  RenderUntilConverged(scene.Window, scene.Mapper);
  scene.Window->Render();
  const atp::RenderStatistics& stats = scene.Mapper->GetStatistics();
  EXPECT_EQ(stats.Uploads, 0u);
  EXPECT_EQ(stats.CacheHits, stats.Patches);
  EXPECT_EQ(stats.CacheMisses, 0u);
  EXPECT_TRUE(stats.Converged);
}

TEST(Mapper, CorruptPatchIsReportedOnceAndNeverDrawn)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  // Corrupt the patch of the deepest node in the file.
  const std::size_t victim = model.NodeCount() - 1;
  const std::size_t offset = std::size_t(model.PatchData(victim) - model.PatchData(0)) +
    model.Header().PatchSectionOffset + model.Node(victim).PatchBytes / 2;
  const std::string corrupt = TempPath("corrupt.atp");
  {
    std::ifstream in(TorusModel(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes[offset] = char(bytes[offset] ^ 0x5A);
    std::ofstream(corrupt, std::ios::binary) << bytes;
  }
  AtpScene scene(corrupt);
  ErrorCounter errors;
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  scene.Mapper->SetTolerancePixels(0.01); // ask for every leaf
  AimCamera(FirstRenderer(scene.Window), 0, 0, 1.0);
  for (int frame = 0; frame < 3; ++frame)
  {
    RenderUntilConverged(scene.Window, scene.Mapper);
  }
  EXPECT_EQ(errors.Errors, 1);
  for (const unsigned n : scene.Mapper->GetDrawnNodes())
  {
    EXPECT_NE(n, victim);
  }
  EXPECT_TRUE(scene.Mapper->GetConverged());
  ::unlink(corrupt.c_str());
}

TEST(Mapper, ModelCutShortWhileDrawnIsReportedOnceAndTheViewGoesOn)
{
  const std::string copy = TempPath("shrinking.atp");
  {
    std::ifstream in(TorusModel(), std::ios::binary);
    std::ofstream(copy, std::ios::binary) << in.rdbuf();
  }
  AtpScene scene(copy);
  ErrorCounter errors;
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  AimCamera(FirstRenderer(scene.Window), 0, 0, 0.3); // far: coarse patches only
  RenderUntilConverged(scene.Window, scene.Mapper);
  const std::size_t coarseTriangles = scene.Mapper->GetStatistics().Triangles;
  ASSERT_EQ(errors.Errors, 0);

  // Another program cuts the mapped file to its first page, then the camera moves in.
  ::truncate(copy.c_str(), 4096);
  scene.Mapper->SetTolerancePixels(0.01);
  AimCamera(FirstRenderer(scene.Window), 0, 0, 1.0);
  for (int frame = 0; frame < 3; ++frame)
  {
    RenderUntilConverged(scene.Window, scene.Mapper);
  }
  EXPECT_EQ(errors.Errors, 1);
  EXPECT_TRUE(scene.Mapper->GetConverged());
  EXPECT_GE(scene.Mapper->GetStatistics().Triangles, coarseTriangles);
  ::unlink(copy.c_str());
}

TEST(Mapper, SeveralRenderersAndWindows)
{
  AtpScene scene;
  vtkRenderer* left = FirstRenderer(scene.Window);
  left->SetViewport(0, 0, 0.5, 1);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0, 1, 1);
  right->AddActor(scene.Actor);
  scene.Window->AddRenderer(right);
  AimCamera(left, 0, 30, 1.0);
  AimCamera(right, 180, -30, 3.0);
  auto other = MakeWindow(200, 150);
  FirstRenderer(other)->AddActor(scene.Actor);
  AimCamera(FirstRenderer(other), 90, 0, 1.0);
  for (int frame = 0; frame < 200; ++frame)
  {
    scene.Window->Render();
    other->Render();
  }
  // One mapper, one decoder: each window still gets the patches it asked for.
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetConverged());
  other->Render();
  EXPECT_TRUE(scene.Mapper->GetConverged());
  // Each drew: the second window's picture is not empty, and the first one's has both halves.
  vtkSmartPointer<vtkImageData> first = atp::CaptureWindow(scene.Window), second = atp::CaptureWindow(other);
  auto lit = [](vtkImageData* image, int x0, int x1) {
    int count = 0;
    int* extent = image->GetExtent();
    for (int y = extent[2]; y <= extent[3]; ++y)
    {
      for (int x = x0; x < x1; ++x)
      {
        count += *static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0)) > 0;
      }
    }
    return count;
  };
  EXPECT_GT(lit(first, 0, Width / 2), 1000);
  EXPECT_GT(lit(first, Width / 2, Width), 1000);
  EXPECT_GT(lit(second, 0, 200), 1000);
  other->Finalize();
}

// A window that has not drawn since the model changed holds the old model's nodes: the other
// window's frames must not read them as the new model's (here: a model of far fewer nodes).
TEST(Mapper, AModelChangedUnderTwoWindows)
{
  const std::string coarse = TempPath("coarse-torus.atp");
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputFileName(ATP_DATA_DIR "/bumpy-torus.ply");
  builder->SetFileName(coarse.c_str());
  ASSERT_EQ(builder->Build(), 1);
  AtpScene scene;
  auto other = MakeWindow(200, 150);
  FirstRenderer(other)->AddActor(scene.Actor);
  AimCamera(FirstRenderer(scene.Window), 30, 40, 1.0);
  AimCamera(FirstRenderer(other), 90, 0, 1.0);
  // Both still loading, the second window last handed patches it has not drawn yet.
  for (int frame = 0; frame < 3; ++frame)
  {
    other->Render();
    scene.Window->Render();
  }
  scene.Reader->SetFileName(coarse.c_str());
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  EXPECT_LT(RenderUntilConverged(other, scene.Mapper), 400);
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  other->Finalize();
  ::unlink(coarse.c_str());
}

// Nothing to draw is nothing to wait for: a render-until-converged loop ends.
TEST(Mapper, NoModelIsConverged)
{
  AtpScene scene("/nonexistent/model.atp");
  ErrorCounter errors;
  scene.Reader->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  scene.Reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  scene.Window->Render();
  EXPECT_GT(errors.Errors, 0);
  EXPECT_TRUE(scene.Mapper->GetConverged());
  EXPECT_EQ(scene.Mapper->GetStatistics().Patches, 0u);

  // A model drawn, then a file that fails: the nodes of the one before are not listed as drawn.
  scene.Reader->SetFileName(TorusModel().c_str());
  EXPECT_LT(RenderUntilConverged(scene.Window, scene.Mapper), 400);
  ASSERT_FALSE(scene.Mapper->GetDrawnNodes().empty());
  scene.Reader->SetFileName("/nonexistent/model.atp");
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetConverged());
  EXPECT_TRUE(scene.Mapper->GetDrawnNodes().empty());
}

// NaN would fail every comparison of the cut; a tolerance out of range is clamped.
TEST(Mapper, RefusesANaNTolerance)
{
  vtkNew<vtkATPMapper> mapper;
  ErrorCounter errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  mapper->SetTolerancePixels(2);
  mapper->SetTolerancePixels(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(errors.Errors, 1);
  EXPECT_EQ(mapper->GetTolerancePixels(), 2);
  mapper->SetTolerancePixels(-1);
  EXPECT_EQ(mapper->GetTolerancePixels(), 1e-3);
  EXPECT_EQ(errors.Errors, 1);
}

TEST(Mapper, BoundsComeFromTheModelBeforeAnyRendering)
{
  AtpScene scene;
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  double bounds[6];
  scene.Mapper->GetBounds(bounds);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(bounds[2 * a], model.Header().BoxMin[a]);
    EXPECT_EQ(bounds[2 * a + 1], model.Header().BoxMax[a]);
  }
}

} // namespace
