// atp: the command line of Adaptive TetraPuzzles for VTK.
#include "atpCalibrate.h"
#include "atpExtractCommand.h"
#include "atpCommandLine.h"
#include "atpConstruction.h"
#include "atpModelCommands.h"
#include "atpMpiBuild.h"
#include "atpPartitioner.h"
#include "atpProgressReport.h"
#include "atpSurfaceGenerator.h"
#include "atpTriangleSource.h"
#include "vtkATPBuilder.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sys/resource.h>

namespace
{
using atp::CommandLine;
using atp::FormatCount;
using atp::FormatDuration;

double PeakResidentMiB()
{
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0; // Linux reports KiB
}

std::vector<std::string> Rest(int argc, char** argv)
{
  return std::vector<std::string>(argv + 2, argv + argc);
}

/// `workers`: the MPI workers when the program runs under mpirun with --mpi, or null.
int Build(int argc, char** argv, atp::MpiJobRunner* workers)
{
  CommandLine cl("build",
    "Builds a multiresolution model (.atp) from a triangle mesh (PLY, OBJ, STL, VTP), streaming\n"
    "it from disk: triangles are sorted into a forest of tetrahedra (6 roots, longest-edge\n"
    "bisection, diamonds split whole) with buckets on disk, then every diamond, bottom-up,\n"
    "simplifies its children's patches with its external boundary locked, and the patches are\n"
    "encoded into OUT. OUT appears only when complete; an existing OUT is replaced atomically.");
  cl.AddPositional("INPUT", "mesh file: .ply (ASCII or binary), .obj, .stl, .vtp");
  cl.AddOption("output", "o", "OUT.atp", "model file to write");
  cl.AddOption("leaf-capacity", "", "N", "most triangles in a leaf tetrahedron", "4000");
  cl.AddOption("patch-budget", "", "N", "most triangles in a tetrahedron of a simplified level",
    "2000");
  cl.AddOption("threads", "j", "N", "worker threads (the model is identical for any count)",
    "every core");
  cl.AddOption("bucket-memory", "", "MiB", "memory for in-memory triangle buckets", "256");
  cl.AddOption("scratch", "", "DIR", "directory for temporary files", "$TMPDIR or /tmp");
  cl.AddFlag("mpi",
    "run the leaf and diamond jobs on MPI worker processes (mpirun -np N: rank 0 coordinates, "
    "ranks 1..N-1 build; the model is identical)");
  cl.AddFlag("quiet", "no progress output, only the summary");
  if (!cl.Parse(Rest(argc, argv)))
  {
    return 0;
  }
  if (!cl.Has("output"))
  {
    throw atp::UsageError("missing -o OUT.atp (see atp build --help)");
  }

  vtkNew<vtkATPBuilder> builder;
  builder->SetInputFileName(cl.Positional(0).c_str());
  builder->SetFileName(cl.Get("output").c_str());
  builder->SetLeafCapacity(int(cl.GetInteger("leaf-capacity", 1, 1 << 30)));
  builder->SetPatchBudget(int(cl.GetInteger("patch-budget", 16, 1 << 20)));
  if (cl.Has("threads"))
  {
    builder->SetNumberOfThreads(int(cl.GetInteger("threads", 1, 1024)));
  }
  builder->SetBucketMemoryMiB(int(cl.GetInteger("bucket-memory", 1, 1 << 20)));
  if (cl.Has("scratch"))
  {
    builder->SetScratchDirectory(cl.Get("scratch").c_str());
  }
  builder->SetJobRunner(workers);

  // Errors are reported once, by us, not also by VTK's output window.
  vtkNew<vtkCallbackCommand> swallowErrors;
  builder->AddObserver(vtkCommand::ErrorEvent, swallowErrors);
  atp::ProgressReport progress("building", 0, "triangles");
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&progress);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
    auto* report = static_cast<atp::ProgressReport*>(client);
    auto* running = static_cast<vtkATPBuilder*>(caller);
    if (*running->GetErrorMessage())
    {
      return; // VTK ends every run at 100%, failed ones too
    }
    report->SetTotal(running->GetExpectedTriangles());
    if (running->GetProgressText())
    {
      report->SetTask(running->GetProgressText());
    }
    report->Update(*static_cast<double*>(call));
  });
  if (!cl.Has("quiet"))
  {
    builder->AddObserver(vtkCommand::ProgressEvent, onProgress);
  }

  const auto start = std::chrono::steady_clock::now();
  const int ok = builder->Build();
  progress.Finish();
  if (!ok)
  {
    std::fprintf(stderr, "atp build: error: %s\n", builder->GetErrorMessage());
    return 1;
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const atp::InputStats& in = builder->GetInputStats();
  const atp::PartitionStats& p = builder->GetPartitionStats();
  std::printf("input: %s vertices, %s faces, %s triangles (%llu degenerate dropped, %llu "
              "boundary edges)\n",
    FormatCount(double(in.VerticesRead)).c_str(), FormatCount(double(in.FacesRead)).c_str(),
    FormatCount(double(in.TrianglesEmitted)).c_str(),
    static_cast<unsigned long long>(in.DegenerateDropped),
    static_cast<unsigned long long>(in.BoundaryEdges));
  const double partitionSeconds = builder->GetPartitionSeconds();
  std::printf("partition: %llu leaves (%llu holding triangles, largest %llu), depth %d, %llu "
              "tetrahedra split, %llu overfull at the deepest level, %.2fs (%s triangles/s)\n",
    static_cast<unsigned long long>(p.Leaves), static_cast<unsigned long long>(p.NonEmptyLeaves),
    static_cast<unsigned long long>(p.LargestLeaf), p.Depth,
    static_cast<unsigned long long>(p.TetrahedraSplit),
    static_cast<unsigned long long>(p.OverfullLeaves), partitionSeconds,
    FormatCount(double(p.Triangles) / std::max(partitionSeconds, 1e-9)).c_str());
  std::printf("buckets: %.1f MiB written to scratch, %.1f MiB read back, scratch peak %.1f MiB\n",
    double(p.Buckets.BytesWritten) / (1 << 20), double(p.Buckets.BytesRead) / (1 << 20),
    double(p.Buckets.PeakScratchBytes) / (1 << 20));
  const atp::ConstructionStats& c = builder->GetConstructionStats();
  std::printf("simplify: %llu diamonds, %s collapses, %llu over budget (locked), coarsest error "
              "%.3g, %.2fs\n",
    static_cast<unsigned long long>(c.Diamonds), FormatCount(double(c.Collapses)).c_str(),
    static_cast<unsigned long long>(c.QuotaMisses), c.CoarsestError,
    builder->GetConstructionSeconds());
  std::printf("scratch: peak %.1f MiB of patches\n", double(c.PeakScratchBytes) / (1 << 20));
  if (workers)
  {
    std::string jobs;
    std::uint64_t peak = 0, sent = 0, received = 0;
    for (const atp::MpiJobRunner::WorkerStats& w : workers->Finish())
    {
      jobs += (jobs.empty() ? "" : "/") + std::to_string(w.Jobs);
      peak = std::max(peak, w.PeakMemoryBytes);
      sent += w.JobBytes;
      received += w.ResultBytes;
    }
    std::printf("mpi: %d workers, jobs per worker %s, %.0f MiB shipped to workers and %.0f MiB "
                "back, coordinator CPU %.1fs, peak memory per worker %.0f MiB (largest)\n",
      workers->Workers(), jobs.c_str(), double(sent) / (1 << 20), double(received) / (1 << 20),
      workers->CoordinatorCpuSeconds(), double(peak) / (1 << 20));
  }
  std::printf("done: %s: %s triangles, %llu nodes, %d levels, %.1f MiB, %.2f bytes/triangle, "
              "%s (%.2fs), %s triangles/s, peak memory %.0f MiB\n",
    cl.Get("output").c_str(), FormatCount(double(p.Triangles)).c_str(),
    static_cast<unsigned long long>(c.Nodes), c.Depth + 1, double(c.FileBytes) / (1 << 20),
    double(c.FileBytes) / double(std::max<std::uint64_t>(1, p.Triangles)),
    FormatDuration(seconds).c_str(), seconds,
    FormatCount(double(p.Triangles) / std::max(seconds, 1e-9)).c_str(), PeakResidentMiB());
  return 0;
}

int Generate(int argc, char** argv)
{
  CommandLine cl("generate",
    "Writes a large test surface (a torus with bumps at several scales) as binary PLY,\n"
    "streaming, so inputs of any size can be made for benchmarks.");
  cl.AddOption("output", "o", "OUT.ply", "PLY file to write");
  cl.AddOption("triangles", "n", "N", "approximate number of triangles", "1000000");
  cl.AddOption("holes", "", "K", "rectangular holes to punch, giving mesh borders", "0");
  if (!cl.Parse(Rest(argc, argv)))
  {
    return 0;
  }
  if (!cl.Has("output"))
  {
    throw atp::UsageError("missing -o OUT.ply (see atp generate --help)");
  }
  atp::SurfaceOptions options;
  options.Triangles = std::uint64_t(cl.GetInteger("triangles", 8, 4000000000LL));
  options.Holes = int(cl.GetInteger("holes", 0, 64));
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t written = atp::WriteBumpyTorusPly(cl.Get("output"), options);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("wrote %s: %llu triangles in %.2fs\n", cl.Get("output").c_str(),
    static_cast<unsigned long long>(written), seconds);
  return 0;
}

void PrintHelp()
{
  std::cout << "usage: atp COMMAND [arguments] [options]\n\n"
               "Adaptive TetraPuzzles for VTK: multiresolution models of huge triangle meshes.\n\n"
               "commands:\n"
               "  build      build a model (.atp) from a mesh file\n"
               "  info       describe a model (--json for machines)\n"
               "  verify     check every checksum, invariant and patch of a model\n"
               "  calibrate  find and store a model's error scale from rendered views\n"
               "  extract    write a level of detail (a camera's cut or a level) as PLY, VTP or STL\n"
               "  generate   write a large test surface as binary PLY\n\n"
               "Run 'atp COMMAND --help' for the options of a command.\n";
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")
  {
    PrintHelp();
    return argc < 2 ? 2 : 0;
  }
  // A file size limit (ulimit -f) must fail the write with an error we report, not kill us.
  std::signal(SIGXFSZ, SIG_IGN);
  const std::string command = argv[1];
  // atp build --mpi: every rank runs this program; ranks other than 0 are workers.
  std::optional<atp::MpiSession> mpi;
  std::unique_ptr<atp::MpiJobRunner> workers; // stopped however rank 0 ends, before MPI is
  if (atp::WantsMpi(argc, argv))
  {
    mpi.emplace(&argc, &argv);
    if (mpi->Rank() > 0)
    {
      try
      {
        return atp::RunMpiWorker(MPI_COMM_WORLD);
      }
      catch (const std::exception& e)
      {
        // The coordinator may be waiting for this worker: end every process.
        std::fprintf(stderr, "atp build: worker %d: error: %s\n", mpi->Rank(), e.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
        return 1;
      }
    }
  }
  try
  {
    if (command == "build")
    {
      if (mpi)
      {
        workers = std::make_unique<atp::MpiJobRunner>(MPI_COMM_WORLD);
      }
      return Build(argc, argv, workers.get());
    }
    if (command == "generate")
    {
      return Generate(argc, argv);
    }
    if (command == "info")
    {
      return atp::InfoCommand(Rest(argc, argv));
    }
    if (command == "verify")
    {
      return atp::VerifyCommand(Rest(argc, argv));
    }
    if (command == "calibrate")
    {
      return atp::CalibrateCommand(Rest(argc, argv));
    }
    if (command == "extract")
    {
      return atp::ExtractCommand(Rest(argc, argv));
    }
    std::fprintf(stderr, "atp: unknown command '%s' (see atp --help)\n", command.c_str());
    return 2;
  }
  catch (const atp::UsageError& e)
  {
    std::fprintf(stderr, "atp %s: %s\n", command.c_str(), e.what());
    return 2;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "atp %s: error: %s\n", command.c_str(), e.what());
    return 1;
  }
}
