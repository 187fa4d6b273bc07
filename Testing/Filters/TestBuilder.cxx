// vtkATPBuilder as a VTK user drives it: polydata or file input, properties, progress events,
// errors reported (not thrown), PrintSelf.
#include "MeshTriangles.h"
#include "atpConstruction.h"
#include "atpCpuTime.h"
#include "atpCutIndex.h"
#include "atpModelFile.h"
#include "atpPartitioner.h"
#include "atpTriangleSource.h"
#include "atpVolumeSlabs.h"
#include "vtkATPBuilder.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkExecutive.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

namespace
{
/// An n x n grid of quads on a wavy sheet: 2 n^2 triangles, 4 n boundary edges.
vtkNew<vtkPolyData> WavySheet(int n)
{
  vtkNew<vtkPoints> points;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      points->InsertNextPoint(i, j, 3 * std::sin(i * 0.3) * std::cos(j * 0.2));
    }
  }
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const vtkIdType a = j * (n + 1) + i;
      const vtkIdType quad[4] = { a, a + 1, a + n + 2, a + n + 1 };
      quads->InsertNextCell(4, quad);
    }
  }
  vtkNew<vtkPolyData> sheet;
  sheet->SetPoints(points);
  sheet->SetPolys(quads);
  return sheet;
}

/// A path for a test's output, removed when the test ends.
struct TemporaryPath
{
  std::string Path;
  explicit TemporaryPath(const std::string& name)
    : Path("/tmp/atp-test-builder-" + std::to_string(::getpid()) + "-" + name)
  {
  }
  ~TemporaryPath() { std::remove(Path.c_str()); }
  const char* c_str() const { return Path.c_str(); }
};

bool Exists(const TemporaryPath& p)
{
  return ::access(p.c_str(), F_OK) == 0;
}

struct ProgressLog
{
  std::vector<double> Values;
};

void Record(vtkObject*, unsigned long, void* client, void* call)
{
  static_cast<ProgressLog*>(client)->Values.push_back(*static_cast<double*>(call));
}
} // namespace

TEST(Builder, PartitionsPolyDataInputWithProgress)
{
  const TemporaryPath model("sheet.atp");
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputData(WavySheet(60));
  builder->SetFileName(model.c_str());
  builder->SetLeafCapacity(100);
  builder->SetPatchBudget(50);
  ProgressLog log;
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(Record);
  progress->SetClientData(&log);
  builder->AddObserver(vtkCommand::ProgressEvent, progress);

  ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
  EXPECT_EQ(builder->GetInputStats().TrianglesEmitted, 2u * 60 * 60);
  EXPECT_EQ(builder->GetInputStats().BoundaryEdges, 4u * 60);
  const atp::PartitionStats& p = builder->GetPartitionStats();
  EXPECT_EQ(p.Triangles, 2u * 60 * 60);
  EXPECT_LE(p.LargestLeaf, 100u);
  EXPECT_GE(p.NonEmptyLeaves, 72u);
  ASSERT_GE(log.Values.size(), 2u);
  EXPECT_EQ(log.Values.front(), 0.0);
  EXPECT_EQ(log.Values.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(log.Values.begin(), log.Values.end()));
  EXPECT_TRUE(Exists(model));
  const atp::ConstructionStats& c = builder->GetConstructionStats();
  EXPECT_EQ(c.Nodes, p.Leaves + p.TetrahedraSplit);
  EXPECT_GT(c.Diamonds, 0u);
  EXPECT_GT(c.StoredTriangles, p.Triangles); // the full resolution plus the coarser levels
  EXPECT_GT(c.FileBytes, 0u);

  // A second Build() runs again (a sink, like vtkWriter::Write).
  log.Values.clear();
  ASSERT_EQ(builder->Build(), 1);
  EXPECT_FALSE(log.Values.empty());
}

// The build reports where its CPU went: every step of construction took some, the steps add up
// to nearly all of what the process used while constructing and never to more, and the phases
// to no more than the whole build.
TEST(Builder, ReportsWhereItsCpuWent)
{
  const TemporaryPath model("cpu.atp");
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputData(WavySheet(250));
  builder->SetFileName(model.c_str());
  builder->SetNumberOfThreads(2);
  const double start = atp::ProcessCpuSeconds();
  ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
  const double build = atp::ProcessCpuSeconds() - start;

  const double partition = builder->GetPartitionCpuSeconds();
  const double construction = builder->GetConstructionCpuSeconds();
  EXPECT_GT(partition, 0);
  EXPECT_GT(construction, 0);
  EXPECT_LE(partition + construction, build);
  const atp::ConstructionCpuSeconds& cpu = builder->GetConstructionStats().Cpu;
  const double steps[] = { cpu.LeafWeld, cpu.LeafEncode, cpu.DiamondMerge, cpu.DiamondSimplify,
    cpu.DiamondEncode, cpu.LoadJobs, cpu.StoreResults, cpu.WriteModel };
  double sum = 0;
  for (std::size_t i = 0; i < std::size(steps); ++i)
  {
    EXPECT_GT(steps[i], 0) << "step " << i;
    sum += steps[i];
  }
  EXPECT_LE(sum, construction);
  EXPECT_GE(sum, 0.8 * construction);
  EXPECT_GT(cpu.DiamondSimplify, cpu.DiamondMerge); // the simplifier is the costly step
}

// The build's figures on quotas and the budget agree with the model it wrote, recomputed from
// its triangle counts: a diamond keeps at most half of what its members' children hold (each
// member's half capped at the budget), and each member at most the budget. A budget of 16 is too
// small for what the members' locked borders hold; with the default, none is over it.
TEST(Builder, CountsQuotaMissesAndPatchesOverTheBudget)
{
  for (const std::uint32_t budget : { 16u, 2000u })
  {
    const TemporaryPath model("budget.atp");
    vtkNew<vtkATPBuilder> builder;
    builder->SetInputData(WavySheet(60));
    builder->SetFileName(model.c_str());
    builder->SetLeafCapacity(400);
    builder->SetPatchBudget(int(budget));
    ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
    const atp::ModelFile file = atp::ModelFile::Open(model.Path);
    const atp::CutIndex diamonds(file);
    std::uint64_t overBudget = 0, overQuota = 0, trianglesOverQuotas = 0;
    for (std::uint32_t d = 0; d < diamonds.DiamondCount(); ++d)
    {
      std::uint64_t total = 0, quota = 0, overCaps = 0;
      for (const std::uint32_t* m = diamonds.MembersBegin(d); m != diamonds.MembersEnd(d); ++m)
      {
        const atp::ModelNode& n = file.Node(*m);
        if (n.Children[0] < 0)
        {
          continue; // a leaf: the input, not simplified
        }
        const std::uint32_t children = file.Node(std::size_t(n.Children[0])).TriangleCount +
          file.Node(std::size_t(n.Children[1])).TriangleCount;
        total += n.TriangleCount;
        quota += std::min(budget, (children + 1) / 2);
        overBudget += n.TriangleCount > budget;
        overCaps += n.TriangleCount > budget ? n.TriangleCount - budget : 0;
      }
      const std::uint64_t over = (total > quota ? total - quota : 0) + overCaps;
      overQuota += over > 0;
      trianglesOverQuotas += over;
    }
    const atp::ConstructionStats& c = builder->GetConstructionStats();
    EXPECT_EQ(c.SimplifiedPatchesOverBudget, overBudget) << "budget " << budget;
    EXPECT_EQ(c.TrianglesOverQuotas, trianglesOverQuotas) << "budget " << budget;
    EXPECT_EQ(c.QuotaMisses, overQuota) << "budget " << budget;
    EXPECT_EQ(overBudget > 0, budget == 16) << "budget " << budget;
  }
}

/// n^3 tetrahedra with edges `size` long, one unit apart: closed specks, as an isosurface's noise.
vtkNew<vtkPolyData> Specks(int n, double size)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  for (int i = 0; i < n * n * n; ++i)
  {
    const double x = i % n, y = i / n % n, z = i / (n * n);
    const vtkIdType first = points->GetNumberOfPoints();
    points->InsertNextPoint(x, y, z);
    points->InsertNextPoint(x + size, y, z);
    points->InsertNextPoint(x, y + size, z);
    points->InsertNextPoint(x, y, z + size);
    const vtkIdType faces[4][3] = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } }; // outward
    for (const vtkIdType* face : faces)
    {
      const vtkIdType corners[3] = { first + face[0], first + face[1], first + face[2] };
      triangles->InsertNextCell(3, corners);
    }
  }
  vtkNew<vtkPolyData> specks;
  specks->SetPoints(points);
  specks->SetPolys(triangles);
  return specks;
}

// No collapse can shrink a tetrahedron: the simplified levels meet their quotas by removing
// whole ones, and say so; their error covers what went.
TEST(Builder, SpecksGoWholeAndAreCounted)
{
  const TemporaryPath model("specks.atp");
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputData(Specks(12, 0.05));
  builder->SetFileName(model.c_str());
  builder->SetLeafCapacity(400);
  ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
  const atp::ConstructionStats& c = builder->GetConstructionStats();
  EXPECT_GT(c.PiecesRemoved, 1000u);
  EXPECT_EQ(c.QuotaMisses, 0u) << "every level halves";
  const atp::ModelFile file = atp::ModelFile::Open(model.Path);
  std::uint64_t rootTriangles = 0;
  for (std::size_t n = 0; n < file.NodeCount(); ++n)
  {
    const atp::ModelNode& node = file.Node(n);
    if (node.Parent < 0)
    {
      rootTriangles += node.TriangleCount;
      EXPECT_GE(node.SaturatedError, 0.05f * std::sqrt(3.f) / 2) << "root " << n;
    }
  }
  EXPECT_LE(rootTriangles, 12u * 12u * 12u * 4u / 2u);
}

TEST(Builder, StreamsAFileToTheSameResult)
{
  const TemporaryPath mesh("sheet.vtp"), fileModel("file.atp"), memoryModel("memory.atp");
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(WavySheet(40));
  writer->SetFileName(mesh.c_str());
  ASSERT_EQ(writer->Write(), 1);

  vtkNew<vtkATPBuilder> fromFile;
  fromFile->SetInputFileName(mesh.c_str());
  fromFile->SetFileName(fileModel.c_str());
  fromFile->SetLeafCapacity(50);
  ASSERT_EQ(fromFile->Build(), 1) << fromFile->GetErrorMessage();
  vtkNew<vtkATPBuilder> fromMemory;
  fromMemory->SetInputData(WavySheet(40));
  fromMemory->SetFileName(memoryModel.c_str());
  fromMemory->SetLeafCapacity(50);
  ASSERT_EQ(fromMemory->Build(), 1) << fromMemory->GetErrorMessage();

  EXPECT_EQ(fromFile->GetPartitionStats().Leaves, fromMemory->GetPartitionStats().Leaves);
  EXPECT_EQ(fromFile->GetPartitionStats().Depth, fromMemory->GetPartitionStats().Depth);
  EXPECT_EQ(fromFile->GetInputStats().BoundaryEdges, 160u);
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  EXPECT_FALSE(bytes(fileModel.Path).empty());
  EXPECT_TRUE(bytes(fileModel.Path) == bytes(memoryModel.Path)) << "the same model, byte for byte";
}

// The fast cache order only reorders each patch's triangles: the same tree, the same
// triangles in every node (so no crack the default order would not have), other bytes, and the
// model says which order it holds.
TEST(Builder, FastCacheOrderReordersTheSamePatches)
{
  const TemporaryPath best("best.atp"), fast("fast.atp");
  for (const bool on : { false, true })
  {
    vtkNew<vtkATPBuilder> builder;
    builder->SetInputData(WavySheet(60));
    builder->SetFileName(on ? fast.c_str() : best.c_str());
    builder->SetLeafCapacity(400);
    builder->SetPatchBudget(200);
    builder->SetFastCacheOrder(on);
    ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
  }
  const atp::ModelFile bestModel = atp::ModelFile::Open(best.Path);
  const atp::ModelFile fastModel = atp::ModelFile::Open(fast.Path);
  EXPECT_EQ(bestModel.Header().Flags & atp::ModelFlagFastCacheOrder, 0u);
  EXPECT_EQ(fastModel.Header().Flags & atp::ModelFlagFastCacheOrder, atp::ModelFlagFastCacheOrder);
  ASSERT_EQ(bestModel.NodeCount(), fastModel.NodeCount());
  ASSERT_GT(bestModel.Header().Depth, 2u);
  std::size_t reordered = 0;
  atp::PatchMesh a, b;
  for (std::size_t i = 0; i < bestModel.NodeCount(); ++i)
  {
    ASSERT_EQ(bestModel.Node(i).Tet, fastModel.Node(i).Tet);
    bestModel.DecodePatch(i, a);
    fastModel.DecodePatch(i, b);
    EXPECT_EQ(atp::test::TriangleSet(a.Positions, a.Indices),
      atp::test::TriangleSet(b.Positions, b.Indices))
      << "node " << i;
    reordered += a.Indices != b.Indices;
  }
  EXPECT_GT(reordered, 0u);
}

TEST(Builder, ReportsErrorsWithoutThrowing)
{
  vtkNew<vtkCallbackCommand> quiet; // keep expected errors out of the test log
  vtkNew<vtkATPBuilder> builder;
  builder->AddObserver(vtkCommand::ErrorEvent, quiet);
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("no input"), std::string::npos);

  builder->SetInputFileName("/nonexistent/mesh.ply");
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("no output"), std::string::npos);

  // Update() without Build()'s own checks says the same.
  builder->Modified();
  builder->Update();
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("no output"), std::string::npos);

  // An output directory that is not there is found before the input is read.
  builder->SetFileName("/nonexistent/dir/never.atp");
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_EQ(std::string(builder->GetErrorMessage()),
    "/nonexistent/dir/never.atp: No such file or directory (its directory /nonexistent/dir/)");

  const TemporaryPath model("never.atp");
  builder->SetFileName(model.c_str());
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_FALSE(Exists(model));
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("/nonexistent/mesh.ply"),
    std::string::npos);

  // What a build expected to read is not left over from the one before.
  builder->SetInputFileName(ATP_DATA_DIR "/bumpy-torus.ply");
  const TemporaryPath built("built.atp");
  builder->SetFileName(built.c_str());
  ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
  EXPECT_GT(builder->GetExpectedTriangles(), 0u);
  builder->SetInputFileName("/nonexistent/mesh.ply");
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_EQ(builder->GetExpectedTriangles(), 0u);

  vtkNew<vtkATPBuilder> empty;
  empty->AddObserver(vtkCommand::ErrorEvent, quiet);
  vtkNew<vtkPolyData> nothing;
  empty->SetInputData(nothing);
  empty->SetFileName(model.c_str());
  EXPECT_EQ(empty->Build(), 0);
  EXPECT_NE(std::string(empty->GetErrorMessage()).find("empty"), std::string::npos);

  // A reader upstream that fails: the executive never asks the builder for data.
  vtkNew<vtkXMLPolyDataReader> missing;
  missing->SetFileName("/nonexistent/mesh.vtp");
  missing->AddObserver(vtkCommand::ErrorEvent, quiet);
  missing->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
  vtkNew<vtkATPBuilder> downstream;
  downstream->AddObserver(vtkCommand::ErrorEvent, quiet);
  downstream->SetInputConnection(missing->GetOutputPort());
  downstream->SetFileName(model.c_str());
  EXPECT_EQ(downstream->Build(), 0);
  EXPECT_FALSE(Exists(model));
  EXPECT_NE(std::string(downstream->GetErrorMessage()).find("input pipeline failed"), std::string::npos);
}

TEST(Builder, IsoValueIsForVolumesOnly)
{
  vtkNew<vtkCallbackCommand> quiet;
  const TemporaryPath model("never.atp");
  vtkNew<vtkATPBuilder> builder;
  builder->AddObserver(vtkCommand::ErrorEvent, quiet);
  builder->SetFileName(model.c_str());
  builder->SetInputFileName("/nonexistent/head.nii.gz");
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("needs an iso value"), std::string::npos)
    << builder->GetErrorMessage();
  builder->SetIsoValue(3);
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("head.nii.gz: cannot open"),
    std::string::npos) << builder->GetErrorMessage();
  builder->SetInputFileName("/nonexistent/mesh.ply");
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("only for volumes"), std::string::npos)
    << builder->GetErrorMessage();
  atp::RawVolumeLayout raw; // a raw layout makes any file a volume
  raw.Dimensions = { { 2, 2, 2 } };
  builder->SetRawVolumeLayout(&raw);
  EXPECT_EQ(builder->Build(), 0);
  EXPECT_NE(std::string(builder->GetErrorMessage()).find("mesh.ply: cannot open"),
    std::string::npos) << builder->GetErrorMessage();
  EXPECT_FALSE(Exists(model));
}

TEST(Builder, PrintsItsProperties)
{
  vtkNew<vtkATPBuilder> builder;
  builder->SetLeafCapacity(1234);
  builder->SetScratchDirectory("/var/tmp");
  builder->FastCacheOrderOn();
  std::ostringstream s;
  builder->Print(s);
  EXPECT_NE(s.str().find("LeafCapacity: 1234"), std::string::npos);
  EXPECT_NE(s.str().find("ScratchDirectory: /var/tmp"), std::string::npos);
  EXPECT_NE(s.str().find("FastCacheOrder: on"), std::string::npos);
}

TEST(Builder, APointNoCellUsesChangesNothing)
{
  // Clip and threshold outputs keep points no cell uses. One far away set the model's box and
  // the grid of its precision: at 1e6 beside a sheet of 0.01 spacing, 512 of 20,000 finest
  // triangles were kept, and their corners moved by up to 0.03.
  vtkNew<vtkPolyData> sheet = WavySheet(60);
  for (vtkIdType i = 0; i < sheet->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sheet->GetPoint(i, p);
    sheet->GetPoints()->SetPoint(i, 0.01 * p[0], 0.01 * p[1], 0.01 * p[2]);
  }
  vtkNew<vtkPolyData> stray;
  stray->DeepCopy(sheet);
  stray->GetPoints()->InsertNextPoint(1e6, 0, -1e6);
  const TemporaryPath plain("plain.atp"), strayed("strayed.atp");
  for (const auto& [mesh, path] : { std::make_pair(sheet.Get(), &plain), std::make_pair(stray.Get(), &strayed) })
  {
    vtkNew<vtkATPBuilder> builder;
    builder->SetInputData(mesh);
    builder->SetFileName(path->c_str());
    builder->SetLeafCapacity(500);
    ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
  }
  std::ifstream a(plain.Path, std::ios::binary), b(strayed.Path, std::ios::binary);
  const std::string plainBytes((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string strayedBytes((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(plainBytes == strayedBytes) << "the unused point changed the model";
  EXPECT_EQ(atp::ModelFile::Open(strayed.Path).Header().InputTriangles, 2u * 60 * 60);
}
