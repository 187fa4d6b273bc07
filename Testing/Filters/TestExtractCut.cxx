// vtkATPReader and vtkATPExtractCut in a VTK pipeline: bounds before data, clear errors for bad
// files, and cuts as ordinary vtkPolyData.
#include "TestModel.h"

#include "atpModelFile.h"
#include "vtkATPExtractCut.h"
#include "vtkATPModel.h"
#include "vtkATPReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkErrorCode.h"
#include "vtkExecutive.h"
#include "vtkFeatureEdges.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <set>
#include <unistd.h>

namespace
{
using namespace atp::test;

vtkIdType OpenEdgeCount(vtkPolyData* mesh)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(mesh);
  edges->BoundaryEdgesOn();
  edges->FeatureEdgesOff();
  edges->NonManifoldEdgesOn();
  edges->ManifoldEdgesOff();
  edges->Update();
  return edges->GetOutput()->GetNumberOfCells();
}

TEST(Reader, PublishesBoundsBeforeReadingData)
{
  vtkNew<vtkATPReader> reader;
  reader->SetFileName(TorusModel().c_str());
  reader->UpdateInformation();
  double bounds[6];
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::BOUNDS(), bounds);
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(bounds[2 * a], model.Header().BoxMin[a]);
    EXPECT_EQ(bounds[2 * a + 1], model.Header().BoxMax[a]);
  }
  reader->Update();
  ASSERT_NE(reader->GetOutput()->GetModelFile(), nullptr);
  EXPECT_EQ(reader->GetOutput()->GetModelFile()->NodeCount(), model.NodeCount());

  // A file that fails to open publishes no bounds: the torus's used to stay, and a camera reset
  // framed a model that was not there.
  vtkNew<vtkCallbackCommand> quiet;
  reader->AddObserver(vtkCommand::ErrorEvent, quiet);
  reader->SetFileName("/nonexistent/model.atp");
  reader->UpdateInformation();
  EXPECT_FALSE(reader->GetOutputInformation(0)->Has(vtkStreamingDemandDrivenPipeline::BOUNDS()));
  reader->SetFileName(TorusModel().c_str());
  reader->UpdateInformation();
  EXPECT_TRUE(reader->GetOutputInformation(0)->Has(vtkStreamingDemandDrivenPipeline::BOUNDS()));
}

TEST(Reader, BadFilesAreClearErrorsAndEmptyOutputs)
{
  std::ifstream in(TorusModel(), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string corruptNodes = bytes;
  corruptNodes[600] = char(corruptNodes[600] ^ 1); // inside the node section
  const std::pair<std::string, std::string> files[] = {
    { "truncated", bytes.substr(0, bytes.size() / 2) },
    { "foreign", "ply\nformat ascii 1.0\nend_header\n" },
    { "empty", "" },
    { "nodes", corruptNodes },
  };
  for (const auto& [name, content] : files)
  {
    const std::string path = TempPath(name + ".atp");
    std::ofstream(path, std::ios::binary) << content;
    vtkNew<vtkATPReader> reader;
    ErrorCounter errors;
    reader->AddObserver(vtkCommand::ErrorEvent, errors.Command);
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_GE(errors.Errors, 1) << name;
    EXPECT_EQ(reader->GetErrorCode(), vtkErrorCode::FileFormatError) << name;
    EXPECT_EQ(reader->GetOutput()->GetModelFile(), nullptr) << name;
    ::unlink(path.c_str());
  }
  vtkNew<vtkATPReader> missing;
  ErrorCounter errors;
  missing->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  missing->SetFileName(TempPath("does-not-exist.atp").c_str());
  missing->Update();
  EXPECT_EQ(missing->GetErrorCode(), vtkErrorCode::CannotOpenFileError);
  EXPECT_EQ(missing->GetOutput()->GetModelFile(), nullptr);
}

TEST(ExtractCut, FinestLevelIsTheInput)
{
  vtkNew<vtkATPReader> reader;
  reader->SetFileName(TorusModel().c_str());
  vtkNew<vtkATPExtractCut> extract;
  extract->SetInputConnection(reader->GetOutputPort());
  extract->Update();
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  vtkPolyData* mesh = extract->GetOutput();
  EXPECT_EQ(std::uint64_t(mesh->GetNumberOfPolys()), model.Header().InputTriangles);
  EXPECT_EQ(std::uint64_t(OpenEdgeCount(mesh)), model.Header().InputBoundaryEdges);
  EXPECT_NE(mesh->GetPointData()->GetNormals(), nullptr);
}

TEST(ExtractCut, CameraCutsWithPatchIds)
{
  vtkNew<vtkATPReader> reader;
  reader->SetFileName(TorusModel().c_str());
  vtkNew<vtkCamera> camera;
  vtkNew<vtkATPExtractCut> extract;
  extract->SetInputConnection(reader->GetOutputPort());
  extract->SetCamera(camera);
  extract->PatchIdsOn();
  extract->FrustumCullingOff();
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  vtkIdType previous = 0;
  for (const double distance : { 60.0, 12.0, 3.0 })
  {
    camera->SetPosition(0, 0, distance); // the camera's change alone updates the filter
    extract->Update();
    vtkPolyData* mesh = extract->GetOutput();
    EXPECT_GT(mesh->GetNumberOfPolys(), previous) << "closer must be finer";
    previous = mesh->GetNumberOfPolys();
    // A whole surface: no open edges but the input's boundary (which simplification may
    // shorten along itself, never lengthen).
    EXPECT_LE(std::uint64_t(OpenEdgeCount(mesh)), model.Header().InputBoundaryEdges);
    auto* ids = vtkIdTypeArray::SafeDownCast(mesh->GetCellData()->GetArray("PatchId"));
    ASSERT_NE(ids, nullptr);
    std::set<vtkIdType> patches;
    for (vtkIdType t = 0; t < ids->GetNumberOfValues(); ++t)
    {
      ASSERT_LT(std::size_t(ids->GetValue(t)), model.NodeCount());
      patches.insert(ids->GetValue(t));
    }
    EXPECT_EQ(vtkIdType(patches.size()), extract->GetPatchCount());
  }
  // Looking away from the model: the frustum leaves nothing.
  extract->FrustumCullingOn();
  camera->SetPosition(0, 0, 30);
  camera->SetFocalPoint(0, 0, 60);
  extract->Update();
  EXPECT_EQ(extract->GetOutput()->GetNumberOfPolys(), 0);
}

TEST(ExtractCut, RefusesNaNToleranceAndEmptyViewports)
{
  vtkNew<vtkATPExtractCut> extract;
  ErrorCounter errors;
  extract->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  extract->SetTolerancePixels(4);
  extract->SetTolerancePixels(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(errors.Errors, 1);
  EXPECT_EQ(extract->GetTolerancePixels(), 4);
  extract->SetTolerancePixels(1e9);
  EXPECT_EQ(extract->GetTolerancePixels(), 1e6);
  extract->SetTolerancePixels(0);
  EXPECT_EQ(extract->GetTolerancePixels(), 1e-3);

  extract->SetViewportSize(640, 480);
  extract->SetViewportSize(-640, 480);
  extract->SetViewportSize(640, 0);
  EXPECT_EQ(errors.Errors, 3);
  EXPECT_EQ(extract->GetViewportSize()[0], 640);
  EXPECT_EQ(extract->GetViewportSize()[1], 480);
  EXPECT_EQ(errors.Errors, 3);
}

TEST(ExtractCut, RefusesACameraWithNoView)
{
  // A camera at NaN, or of parallel scale 0, gave some arbitrary level without a word.
  vtkNew<vtkATPReader> reader;
  reader->SetFileName(TorusModel().c_str());
  vtkNew<vtkATPExtractCut> extract;
  extract->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 10);
  extract->SetCamera(camera);
  extract->Update();
  ASSERT_GT(extract->GetOutput()->GetNumberOfPolys(), 0);
  ErrorCounter errors;
  extract->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  extract->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::function<void()> breakers[] = {
    [&] { camera->SetPosition(nan, 0, 10); },
    [&] { camera->SetFocalPoint(0, std::numeric_limits<double>::infinity(), 0); },
    [&] {
      camera->ParallelProjectionOn();
      camera->SetParallelScale(0);
    },
  };
  // A parallel camera with a projection of its own does not use its parallel scale.
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0);
  vtkNew<vtkMatrix4x4> projection;
  projection->SetElement(0, 0, 0.5);
  projection->SetElement(1, 1, 0.5);
  projection->SetElement(2, 2, -0.1);
  camera->SetExplicitProjectionTransformMatrix(projection);
  camera->UseExplicitProjectionTransformMatrixOn();
  extract->Update();
  EXPECT_GT(extract->GetOutput()->GetNumberOfPolys(), 0);
  EXPECT_EQ(errors.Errors, 0);
  camera->UseExplicitProjectionTransformMatrixOff();
  for (const auto& breakCamera : breakers)
  {
    camera->SetPosition(0, 0, 10);
    camera->SetFocalPoint(0, 0, 0);
    camera->ParallelProjectionOff();
    extract->Update();
    ASSERT_GT(extract->GetOutput()->GetNumberOfPolys(), 0);
    const int before = errors.Errors;
    breakCamera();
    extract->Update();
    EXPECT_GT(errors.Errors, before);
    EXPECT_EQ(extract->GetOutput()->GetNumberOfPolys(), 0);
  }
}

TEST(ExtractCut, CorruptPatchIsAnError)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  std::ifstream in(TorusModel(), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t offset = model.Header().PatchSectionOffset + model.Node(0).PatchOffset + 40;
  bytes[offset] = char(bytes[offset] ^ 0x10);
  const std::string path = TempPath("corrupt-patch.atp");
  std::ofstream(path, std::ios::binary) << bytes;
  vtkNew<vtkATPReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkATPExtractCut> extract;
  extract->SetInputConnection(reader->GetOutputPort());
  extract->SetLevel(0);
  ErrorCounter errors;
  extract->AddObserver(vtkCommand::ErrorEvent, errors.Command);
  extract->Update();
  EXPECT_GE(errors.Errors, 1);
  EXPECT_EQ(extract->GetOutput()->GetNumberOfPolys(), 0);
  ::unlink(path.c_str());
}

} // namespace
