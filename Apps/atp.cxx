// atp: the command line of Adaptive TetraPuzzles for VTK.
#include "atpBenchCommand.h"
#include "atpCalibrate.h"
#include "atpExtractCommand.h"
#include "atpCommandLine.h"
#include "atpConstruction.h"
#include "atpModelCommands.h"
#include "atpMpiBuild.h"
#include "atpPendingFile.h"
#include "atpPartitioner.h"
#include "atpProcessMemory.h"
#include "atpProgressReport.h"
#include "atpSurfaceGenerator.h"
#include "atpSlabContour.h"
#include "atpTriangleSource.h"
#include "atpVolumeSlabs.h"
#include "vtkATPBuilder.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <unistd.h>

namespace
{
using atp::CommandLine;
using atp::FormatCount;
using atp::FormatDuration;
using atp::PeakResidentMiB;

std::vector<std::string> Rest(int argc, char** argv)
{
  return std::vector<std::string>(argv + 2, argv + argc);
}

/// The volume options of atp build: mistakes are usage errors, caught before reading anything.
void SetVolumeOptions(const CommandLine& cl, vtkATPBuilder* builder)
{
  const std::string& input = cl.Positional(0);
  const bool raw = cl.Has("dims");
  for (const char* rawOnly : { "type", "spacing", "origin", "big-endian" })
  {
    if (cl.Has(rawOnly) && !raw)
    {
      throw atp::UsageError(std::string("--") + rawOnly + " is for raw volumes, which need --dims");
    }
  }
  if (!raw && !atp::IsVolumeFileName(input))
  {
    if (cl.Has("iso") || cl.Has("slab"))
    {
      throw atp::UsageError(std::string("--") + (cl.Has("iso") ? "iso" : "slab") +
        " is for volumes (.nii, .nii.gz, .vti, or raw with --dims); " + input +
        " is none of these, and a raw volume needs --dims X,Y,Z");
    }
    return;
  }
  if (!cl.Has("iso"))
  {
    throw atp::UsageError("a volume needs --iso VALUE, the voxel value of the surface");
  }
  builder->SetIsoValue(cl.GetNumber("iso", -1e300, 1e300));
  builder->SetSlabSlices(int(cl.GetInteger("slab", 2, 1 << 20)));
  if (!raw)
  {
    return;
  }
  atp::RawVolumeLayout layout;
  const std::vector<double> dims = cl.GetNumbers("dims", 3);
  for (int axis = 0; axis < 3; ++axis)
  {
    if (dims[axis] < 1 || dims[axis] > (1 << 30) || dims[axis] != std::floor(dims[axis]))
    {
      throw atp::UsageError("--dims must be 3 whole numbers from 1 to 2^30, got '" +
        cl.Get("dims") + "'");
    }
    layout.Dimensions[axis] = int(dims[axis]);
  }
  if (!atp::ParseVoxelType(cl.Get("type"), layout.Type))
  {
    throw atp::UsageError(
      "--type must be uint8, int16, uint16 or float32, got '" + cl.Get("type") + "'");
  }
  const std::vector<double> spacing = cl.GetNumbers("spacing", 3);
  const std::vector<double> origin = cl.GetNumbers("origin", 3);
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!(spacing[axis] > 0))
    {
      throw atp::UsageError("--spacing must be 3 positive numbers, got '" + cl.Get("spacing") + "'");
    }
    layout.Spacing[axis] = spacing[axis];
    layout.Origin[axis] = origin[axis];
  }
  layout.BigEndian = cl.Has("big-endian");
  builder->SetRawVolumeLayout(&layout);
}

/// `workers`: the MPI workers when the program runs under mpirun with --mpi, or null.
int Build(int argc, char** argv, atp::MpiJobRunner* workers)
{
  CommandLine cl("build",
    "Builds a multiresolution model (.atp) from a triangle mesh (PLY, OBJ, STL, VTP), streaming\n"
    "it from disk: triangles are sorted into a forest of tetrahedra (6 roots, longest-edge\n"
    "bisection, diamonds split whole) with buckets on disk, then every diamond, bottom-up,\n"
    "simplifies its children's patches with its external boundary locked, and the patches are\n"
    "encoded into OUT. OUT appears only when complete; an existing OUT is replaced atomically.\n"
    "\n"
    "A volume (NIfTI .nii/.nii.gz, VTK .vti, or raw voxels with --dims and --type) gives the\n"
    "isosurface at --iso, contoured slab by slab (--slab slices, consecutive slabs sharing one)\n"
    "and welded into the surface of one whole-volume contour, one vertex per position. Every\n"
    "format is read one slab at a time through VTK's readers, so memory holds one slab; but a\n"
    ".nii.gz is decompressed from its start for every slab (time grows with the square of the\n"
    "slab count: use a large --slab, or gunzip it first).");
  cl.AddPositional("INPUT", "mesh file (.ply ASCII or binary, .obj, .stl, .vtp) or volume "
                            "(.nii, .nii.gz, .vti, raw)");
  cl.AddOption("output", "o", "OUT.atp", "model file to write");
  cl.AddOption("iso", "", "VALUE", "volumes: the voxel value of the surface (required)");
  cl.AddOption("slab", "", "N", "volumes: Z slices contoured at a time",
    std::to_string(atp::DefaultSlabSlices));
  cl.AddOption("dims", "", "X,Y,Z", "raw volumes: voxels along x, y and z (x fastest in the file)");
  cl.AddOption("type", "", "TYPE", "raw volumes: uint8, int16, uint16 or float32", "uint8");
  cl.AddOption("spacing", "", "SX,SY,SZ", "raw volumes: voxel size", "1,1,1");
  cl.AddOption("origin", "", "OX,OY,OZ", "raw volumes: position of the first voxel", "0,0,0");
  cl.AddFlag("big-endian", "raw volumes: voxels are big-endian (default little-endian)");
  cl.AddOption("leaf-capacity", "", "N", "most triangles in a leaf tetrahedron", "4000");
  cl.AddOption("patch-budget", "", "N", "most triangles in a tetrahedron of a simplified level (it also keeps at most half of its children's)",
    "2000");
  cl.AddFlag("fast-cache-order",
    "order triangles with meshoptimizer's FIFO vertex-cache optimizer: a build about 12% faster, "
    "a model about 6% larger");
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
  if (atp::FileExtension(cl.Get("output")) != ".atp")
  {
    // A model under a mesh's name would replace the mesh, and be read as one.
    throw atp::UsageError("-o " + cl.Get("output") + ": a model is written to a name ending in .atp");
  }

  vtkNew<vtkATPBuilder> builder;
  builder->SetInputFileName(cl.Positional(0).c_str());
  SetVolumeOptions(cl, builder);
  builder->SetFileName(cl.Get("output").c_str());
  builder->SetLeafCapacity(int(cl.GetInteger("leaf-capacity", 1, 1 << 30)));
  builder->SetPatchBudget(int(cl.GetInteger("patch-budget", 16, 1 << 20)));
  builder->SetFastCacheOrder(cl.Has("fast-cache-order"));
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

  // Errors and warnings are reported once, by us, not also by VTK's output window.
  vtkNew<vtkCallbackCommand> reportedHere;
  builder->AddObserver(vtkCommand::ErrorEvent, reportedHere);
  builder->AddObserver(vtkCommand::WarningEvent, reportedHere);
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
  if (const atp::SlabContourStats* volume = builder->GetVolumeStats())
  {
    std::printf("volume: %dx%dx%d voxels, values %g to %g, isosurface at %g in %d slabs: %s "
                "vertices, %s triangles\n",
      volume->Dimensions[0], volume->Dimensions[1], volume->Dimensions[2], volume->DataRange[0],
      volume->DataRange[1], builder->GetIsoValue(), volume->Slabs,
      FormatCount(double(volume->Vertices)).c_str(),
      FormatCount(double(volume->Triangles)).c_str());
  }
  const atp::InputStats& in = builder->GetInputStats();
  const atp::PartitionStats& p = builder->GetPartitionStats();
  const atp::ConstructionStats& c = builder->GetConstructionStats();
  std::string shared;
  if (in.BoundaryUnchecked)
  {
    shared = "; too many edges open by vertex index to check by position: none kept as boundary";
  }
  else if (in.SharedOpenEdges > 0)
  {
    shared = "; " + std::to_string(in.SharedOpenEdges) +
      " edges open by vertex index are shared by position (unwelded vertices or edges of 3+ "
      "triangles): locked, not boundary";
  }
  const std::string repeated = c.RepeatedTrianglesDropped == 0
    ? std::string()
    : ", " + std::to_string(c.RepeatedTrianglesDropped) + " repeated dropped";
  std::printf("input: %s vertices, %s faces, %s triangles (%llu degenerate dropped%s, %llu "
              "boundary edges%s)\n",
    FormatCount(double(in.VerticesRead)).c_str(), FormatCount(double(in.FacesRead)).c_str(),
    FormatCount(double(in.TrianglesEmitted - c.RepeatedTrianglesDropped)).c_str(),
    static_cast<unsigned long long>(in.DegenerateDropped), repeated.c_str(),
    static_cast<unsigned long long>(in.BoundaryEdges), shared.c_str());
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
  std::printf("simplify: %llu diamonds, %s collapses, %s pieces removed whole, %llu diamonds over quota "
              "(%s triangles over), %llu simplified patches over the budget, coarsest error %.3g, %.2fs\n",
    static_cast<unsigned long long>(c.Diamonds), FormatCount(double(c.Collapses)).c_str(),
    FormatCount(double(c.PiecesRemoved)).c_str(), static_cast<unsigned long long>(c.QuotaMisses),
    FormatCount(double(c.TrianglesOverQuotas)).c_str(),
    static_cast<unsigned long long>(c.SimplifiedPatchesOverBudget), c.CoarsestError,
    builder->GetConstructionSeconds());
  // Where the CPU went: the jobs' steps and loads wherever they ran, the rest on the calling
  // thread.
  const atp::ConstructionCpuSeconds& cpu = c.Cpu;
  std::printf("cpu: partition %.2fs, construction %.2fs in this process; jobs: leaves %.2fs (weld "
              "%.2fs, encode %.2fs), diamonds %.2fs (merge %.2fs, simplify %.2fs, encode %.2fs); "
              "loading jobs %.2fs, storing results %.2fs, writing the model %.2fs\n",
    builder->GetPartitionCpuSeconds(), builder->GetConstructionCpuSeconds(),
    cpu.LeafWeld + cpu.LeafEncode, cpu.LeafWeld, cpu.LeafEncode,
    cpu.DiamondMerge + cpu.DiamondSimplify + cpu.DiamondEncode, cpu.DiamondMerge,
    cpu.DiamondSimplify, cpu.DiamondEncode, cpu.LoadJobs, cpu.StoreResults, cpu.WriteModel);
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
  if (*builder->GetWarningMessage())
  {
    std::fflush(stdout); // after the figures, also where both go to one pipe
    std::fprintf(stderr, "atp build: warning: %s\n", builder->GetWarningMessage());
  }
  return 0;
}

int Generate(int argc, char** argv)
{
  CommandLine cl("generate",
    "Writes a large test surface (a torus with bumps at several scales) as binary PLY,\n"
    "streaming, so inputs of any size can be made for benchmarks.");
  cl.AddOption("output", "o", "OUT.ply", "PLY file to write");
  cl.AddOption("triangles", "n", "N", "number of triangles (at least; holes remove some)", "1000000");
  cl.AddOption("holes", "", "K", "rectangular holes to punch, giving mesh borders", "0");
  if (!cl.Parse(Rest(argc, argv)))
  {
    return 0;
  }
  if (!cl.Has("output"))
  {
    throw atp::UsageError("missing -o OUT.ply (see atp generate --help)");
  }
  const std::string& output = cl.Get("output");
  if (atp::FileExtension(output) != ".ply")
  {
    // PLY under another name would be read as what the name says.
    throw atp::UsageError("-o " + output + ": the surface is written as PLY, to a name ending in .ply");
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

/// atp view: runs atp-view (the Qt viewer, a program of its own so that atp needs no display
/// and no Qt), from the directory atp itself is in.
int View(int argc, char** argv)
{
  char self[4096];
  const ssize_t length = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (length <= 0)
  {
    throw std::runtime_error("cannot find the directory of atp");
  }
  std::string viewer(self, std::size_t(length));
  viewer = viewer.substr(0, viewer.rfind('/') + 1) + "atp-view";
  std::vector<char*> arguments{ const_cast<char*>("atp-view") };
  arguments.insert(arguments.end(), argv + 2, argv + argc);
  arguments.push_back(nullptr);
  ::execv(viewer.c_str(), arguments.data());
  throw std::runtime_error("cannot run " + viewer + ": " + std::strerror(errno));
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
               "  bench      time the standard flythrough of a model: CSV, summary, plot, speed-up\n"
               "  view       show a model in the desktop viewer (atp-view)\n"
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
  // Inputs and scratch files are read through memory maps: when another program truncates one
  // meanwhile, or a sparse scratch file finds its disk full, the next access past what is there
  // raises SIGBUS. A message and exit code 1, no partial output, not a crash (models are read
  // through CopyFromMapping, whose own handler reports it as an error and passes others here).
  struct sigaction mappedFault{};
  mappedFault.sa_flags = SA_SIGINFO;
  mappedFault.sa_sigaction = [](int, siginfo_t* info, void*) {
    static const char mapped[] = "atp: error: a mapped file could not be read or written (another "
                                 "program truncated it, or its disk is full)\n";
    static const char other[] = "atp: error: bus error (a hardware memory error or a misaligned "
                                "access)\n";
    const bool isMapped = info && info->si_code == BUS_ADRERR;
    atp::RemovePendingFiles();
    [[maybe_unused]] const ssize_t written = isMapped
      ? ::write(STDERR_FILENO, mapped, sizeof mapped - 1)
      : ::write(STDERR_FILENO, other, sizeof other - 1);
    ::_exit(1);
  };
  ::sigaction(SIGBUS, &mappedFault, nullptr);
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
    if (command == "bench")
    {
      return atp::BenchCommand(Rest(argc, argv));
    }
    if (command == "view")
    {
      return View(argc, argv);
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
