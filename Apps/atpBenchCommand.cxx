#include "atpBenchCommand.h"

#include "atpBenchPlot.h"
#include "atpCommandLine.h"
#include "atpFlythrough.h"
#include "atpModelFile.h"
#include "atpOffscreenWindow.h"
#include "atpPendingFile.h"
#include "atpPngFile.h"
#include "atpProcessMemory.h"
#include "atpProgressReport.h"
#include "atpRenderStatistics.h"
#include "atpTriangleSource.h"
#include "atpFirstVtkError.h"
#include "atpWindowImage.h"
#include "vtkATPMapper.h"
#include "vtkATPModel.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

namespace atp
{

namespace
{
/// An offscreen window drawing `actor` with a glossy material (the paper's inspection
/// setting), the same for both mappers so their pictures compare.
vtkSmartPointer<vtkRenderWindow> OffscreenWindow(int width, int height, vtkActor* actor)
{
  vtkSmartPointer<vtkRenderWindow> window = NewOffscreenWindow(width, height);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  window->AddRenderer(renderer);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(30);
  return window;
}

/// VTK's reader for the mesh format `path` names by its extension; null when there is none.
vtkSmartPointer<vtkAlgorithm> MeshReaderFor(const std::string& path)
{
  const std::string extension = FileExtension(path);
  if (extension == ".ply")
  {
    auto reader = vtkSmartPointer<vtkPLYReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  if (extension == ".obj")
  {
    auto reader = vtkSmartPointer<vtkOBJReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  if (extension == ".stl")
  {
    auto reader = vtkSmartPointer<vtkSTLReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  if (extension == ".vtp")
  {
    auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  return nullptr;
}

/// The full-resolution mesh at `path` with smooth point normals, as vtkPolyDataMapper draws it
/// best, read by `reader` (VTK's for its format). Throws std::runtime_error naming the file and
/// the problem.
vtkSmartPointer<vtkPolyData> ReadFullMesh(const std::string& path, vtkAlgorithm* reader)
{
  FirstVtkError errors;
  errors.Watch(reader);
  vtkNew<vtkPolyDataNormals> normals;
  errors.Watch(normals);
  normals->SetInputConnection(reader->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->Update();
  if (!errors.Message.empty())
  {
    throw std::runtime_error(path + ": " + errors.Message);
  }
  if (normals->GetOutput()->GetNumberOfPolys() == 0)
  {
    throw std::runtime_error(path + ": no triangles read");
  }
  vtkSmartPointer<vtkPolyData> mesh = normals->GetOutput();
  return mesh;
}

void WriteCsv(std::ostream& out, const std::vector<double>& seconds,
  const std::vector<RenderStatistics>& statistics)
{
  out << "frame,seconds,patches,triangles,cache_hits,cache_misses,uploads,upload_bytes,"
         "cache_bytes,cut_seconds,upload_seconds,draw_seconds,converged\n";
  for (std::size_t f = 0; f < seconds.size(); ++f)
  {
    const RenderStatistics& s = statistics[f];
    out << f << ',' << seconds[f] << ',' << s.Patches << ',' << s.Triangles << ','
        << s.CacheHits << ',' << s.CacheMisses << ',' << s.Uploads << ',' << s.UploadBytes << ','
        << s.CacheBytes << ',' << s.CutSeconds << ',' << s.UploadSeconds << ','
        << s.DrawSeconds << ',' << s.Converged << '\n';
  }
}

/// An output option's pending file, created now (an unwritable place, or one of the `inputs`,
/// is reported before the flythrough), or none when the option is not given.
std::optional<PendingFile> Output(const CommandLine& cl, const std::string& option,
  const std::string& what, const std::vector<std::string>& inputs)
{
  if (!cl.Has(option))
  {
    return std::nullopt;
  }
  return std::make_optional<PendingFile>(cl.Get(option), what, inputs);
}

/// The still camera of the last frame is rendered again until its cut is complete, for the
/// picture and the comparison, at most this many times.
constexpr int MaxConvergingFrames = 200;

struct Settings
{
  std::string ModelPath;
  int Frames = 0, Width = 0, Height = 0;
  double Tolerance = 1;
  long long CacheMiB = 0;
  bool Prefetching = true;
  bool Quiet = false;
};

/// The flythrough of vtkATPMapper: what each frame took and did, and the final frame.
struct AtpRun
{
  double Bounds[6];
  std::vector<double> Seconds;
  std::vector<RenderStatistics> Statistics;
  RenderStatistics Last;     ///< the path's last frame
  int ConvergingFrames = 0;  ///< frames rendered after the path until the cut was complete
  bool Converged = false;    ///< whether it was, within MaxConvergingFrames
  vtkSmartPointer<vtkImageData> FinalFrame;
  double StartMiB = 0, FinalMiB = 0, PeakMiB = 0;
  ResidentKinds Final;  ///< FinalMiB by kind
  std::string Renderer; ///< the OpenGL renderer that drew it
};

/// The same path with vtkPolyDataMapper on the full-resolution mesh.
struct FullRun
{
  std::vector<double> Seconds;
  vtkIdType Triangles = 0;
  double ImageDifference = 0; ///< against the converged final frame of vtkATPMapper
};

/// A frame-by-frame progress line on standard error, unless quiet.
std::function<void(int)> Progress(ProgressReport& report, const Settings& settings)
{
  return [&report, &settings](int frame) {
    if (!settings.Quiet)
    {
      report.Update(double(frame + 1) / settings.Frames);
    }
  };
}

AtpRun FlyAtp(const Settings& settings, const std::shared_ptr<const ModelFile>& file)
{
  vtkNew<vtkATPModel> model;
  model->SetModelFile(file);
  vtkNew<vtkATPMapper> mapper;
  FirstVtkError errors;
  errors.Watch(mapper);
  mapper->SetInputData(model);
  mapper->SetTolerancePixels(settings.Tolerance);
  mapper->SetCacheBudget(vtkTypeInt64(settings.CacheMiB) << 20);
  mapper->SetPrefetching(settings.Prefetching);
  mapper->ScalarVisibilityOff(); // as the full-resolution mapper: the same pictures
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkSmartPointer<vtkRenderWindow> window =
    OffscreenWindow(settings.Width, settings.Height, actor);

  AtpRun run;
  mapper->GetBounds(run.Bounds);
  run.StartMiB = ResidentMiB();
  ProgressReport report("atp flythrough", std::uint64_t(settings.Frames), "frames");
  const std::function<void(int)> progress = Progress(report, settings);
  run.Seconds = FlyThrough(window, run.Bounds, settings.Frames, [&](int frame) {
    run.Statistics.push_back(mapper->GetStatistics());
    progress(frame);
  });
  report.Finish();
  run.Last = mapper->GetStatistics();
  for (; run.ConvergingFrames < MaxConvergingFrames && !mapper->GetConverged();
       ++run.ConvergingFrames)
  {
    window->Render();
  }
  run.Converged = mapper->GetConverged();
  if (!errors.Message.empty())
  {
    throw std::runtime_error(errors.Message); // a corrupt patch: it names the file and node
  }
  run.FinalFrame = CaptureWindow(window);
  run.Renderer = RendererName(window);
  run.FinalMiB = ResidentMiB();
  run.Final = ResidentByKind();
  run.PeakMiB = std::max(PeakResidentMiB(), run.FinalMiB); // two counters, sampled apart
  return run;
}

FullRun FlyFull(const Settings& settings, const std::string& path, vtkAlgorithm* reader,
  const AtpRun& atp)
{
  vtkSmartPointer<vtkPolyData> mesh = ReadFullMesh(path, reader);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkSmartPointer<vtkRenderWindow> window =
    OffscreenWindow(settings.Width, settings.Height, actor);
  FullRun run;
  run.Triangles = mesh->GetNumberOfPolys();
  ProgressReport report("full-resolution flythrough", std::uint64_t(settings.Frames), "frames");
  run.Seconds = FlyThrough(window, atp.Bounds, settings.Frames, Progress(report, settings));
  report.Finish();
  vtkNew<vtkImageDifference> difference;
  difference->SetInputData(CaptureWindow(window));
  difference->SetImageData(atp.FinalFrame);
  difference->SetThreshold(32);
  difference->Update();
  run.ImageDifference = difference->GetThresholdedError();
  return run;
}

void PrintAtpSummary(FILE* out, const Settings& settings, const AtpRun& run)
{
  std::vector<double> cut, cutShare, overhead, patches, triangles;
  double totalTriangles = 0, totalSeconds = 0;
  for (std::size_t f = 0; f < run.Seconds.size(); ++f)
  {
    const RenderStatistics& s = run.Statistics[f];
    cut.push_back(s.CutSeconds);
    cutShare.push_back(s.CutSeconds / run.Seconds[f]);
    overhead.push_back((s.CutSeconds + s.UploadSeconds + s.DrawSeconds) / run.Seconds[f]);
    patches.push_back(double(s.Patches));
    triangles.push_back(double(s.Triangles));
    totalTriangles += double(s.Triangles);
    totalSeconds += run.Seconds[f];
  }
  const double modelMiB = double(std::filesystem::file_size(settings.ModelPath)) / 1048576.0;
  std::fprintf(out,
    "model: %s, %.1f MiB, %d frames at %dx%d, tolerance %g px, cache %lld MiB, prefetch %s\n",
    settings.ModelPath.c_str(), modelMiB, settings.Frames, settings.Width, settings.Height,
    settings.Tolerance, settings.CacheMiB, settings.Prefetching ? "on" : "off");
  std::fprintf(out, "renderer: %s\n", run.Renderer.c_str());
  std::fprintf(out,
    "atp: frame time median %.2f ms, p95 %.2f ms; %.2fM triangles/s; triangles/frame median "
    "%.0f, max %.0f; patches/frame median %.0f, max %.0f\n",
    1e3 * Percentile(run.Seconds, 0.5), 1e3 * Percentile(run.Seconds, 0.95),
    totalTriangles / totalSeconds / 1e6, Percentile(triangles, 0.5), Percentile(triangles, 1.0),
    Percentile(patches, 0.5), Percentile(patches, 1.0));
  std::fprintf(out,
    "atp: cut %.3f ms median (%.1f%% of the frame); CPU overhead (cut, uploads, draw calls) "
    "%.1f%% median, %.1f%% p95 of the frame\n",
    1e3 * Percentile(cut, 0.5), 100 * Percentile(cutShare, 0.5), 100 * Percentile(overhead, 0.5),
    100 * Percentile(overhead, 0.95));
  const RenderStatistics& last = run.Last;
  std::fprintf(out,
    "atp: decoded %llu patches in %.2f s of background time; cache %.1f MiB in a %.1f MiB "
    "buffer, %llu evictions; "
    "prefetch %llu passes, %llu pages advised; final frame %s after %d more frames\n",
    static_cast<unsigned long long>(last.DecodedPatches), last.DecodeSeconds,
    double(last.CacheBytes) / 1048576.0, double(last.CacheBufferBytes) / 1048576.0,
    static_cast<unsigned long long>(last.Evictions),
    static_cast<unsigned long long>(last.PrefetchPasses),
    static_cast<unsigned long long>(last.PrefetchAdvisedPages),
    run.Converged ? "complete" : "still incomplete", run.ConvergingFrames);
  std::fprintf(out,
    "atp: resident memory %.1f MiB at start, %.1f MiB at the end (%.2f%% of the model file; "
    "%.1f MiB anonymous, %.1f MiB mapped from files), peak %.1f MiB\n",
    run.StartMiB, run.FinalMiB, 100 * run.FinalMiB / modelMiB, run.Final.AnonymousMiB,
    run.Final.FileMiB, run.PeakMiB);
}

void PrintComparison(FILE* out, const std::string& path, const AtpRun& atp, const FullRun& full)
{
  const double fullMedian = Percentile(full.Seconds, 0.5);
  std::fprintf(out, "full: %s, %lld triangles, frame time median %.2f ms, p95 %.2f ms\n",
    path.c_str(), static_cast<long long>(full.Triangles), 1e3 * fullMedian,
    1e3 * Percentile(full.Seconds, 0.95));
  std::fprintf(out,
    "speedup=%.2f image_difference=%.4f (vtkImageDifference, intensity threshold 32, final "
    "frame)\n",
    fullMedian / Percentile(atp.Seconds, 0.5), full.ImageDifference);
}
} // namespace

int BenchCommand(const std::vector<std::string>& arguments)
{
  CommandLine cl("bench",
    "Flies the standard path around a model offscreen (a full orbit, zooming from the whole\n"
    "model to a close-up and back, like the paper's inspection session) with vtkATPMapper,\n"
    "timing every frame to completion, and prints per-frame statistics as CSV and a summary.\n"
    "Draws through X, or without a display on an EGL device (a headless GPU; else run under\n"
    "xvfb-run -a); the summary names the renderer. With --compare-full, the same path is drawn\n"
    "by vtkPolyDataMapper on the full-resolution mesh, and the summary ends with a line\n"
    "holding speedup=<full median frame time / atp median frame time> and the image\n"
    "difference of the two at the final frame. Output files appear only when all are complete.");
  cl.AddPositional("MODEL", "a .atp model");
  cl.AddOption("frames", "", "N", "frames of the path", "450");
  cl.AddOption("size", "", "WxH", "window size in pixels", "800x600");
  cl.AddOption("tolerance", "", "PX", "largest screen-space error in pixels", "1");
  cl.AddOption("cache", "", "MiB", "GPU memory for patches", "512");
  cl.AddFlag("no-prefetch", "no speculative prefetching");
  cl.AddOption("csv", "", "FILE",
    "per-frame statistics; '-': standard output, the summary then goes to standard error", "-");
  cl.AddOption("plot", "", "FILE.png",
    "the paper's figure 7: frame time, triangles, patches, cache misses and uploads per frame");
  cl.AddOption("plot-size", "", "WxH", "plot size in pixels", "800x1000");
  cl.AddOption("image", "", "FILE.png", "the final frame, once every patch it needs is drawn");
  cl.AddOption("compare-full", "", "INPUT",
    "the full-resolution mesh (.ply, .obj, .stl, .vtp) to compare with vtkPolyDataMapper");
  cl.AddFlag("quiet", "no progress output");
  if (!cl.Parse(arguments))
  {
    return 0;
  }
  Settings settings;
  settings.ModelPath = cl.Positional(0);
  settings.Frames = int(cl.GetInteger("frames", 2, 1000000));
  cl.GetSize("size", settings.Width, settings.Height);
  settings.Tolerance = cl.GetNumber("tolerance", 1e-3, 1e6);
  settings.CacheMiB = cl.GetInteger("cache", 1, 1 << 24);
  settings.Prefetching = !cl.Has("no-prefetch");
  settings.Quiet = cl.Has("quiet");
  int plotWidth = 0, plotHeight = 0;
  cl.GetSize("plot-size", plotWidth, plotHeight);
  for (const char* option : { "plot", "image" })
  {
    if (cl.Has(option) && FileExtension(cl.Get(option)) != ".png")
    {
      throw UsageError(std::string("--") + option + " must name a .png file, got '" +
        cl.Get(option) + "'");
    }
  }
  // Each output is a file of its own: two under one name would write over each other.
  std::vector<std::filesystem::path> outputs;
  for (const char* option : { "csv", "plot", "image" })
  {
    if (cl.Has(option) && cl.Get(option) != "-")
    {
      const std::filesystem::path path = std::filesystem::absolute(cl.Get(option)).lexically_normal();
      if (std::find(outputs.begin(), outputs.end(), path) != outputs.end())
      {
        throw UsageError(std::string("--") + option + " " + cl.Get(option) + ": another output is written there too");
      }
      outputs.push_back(path);
    }
  }
  const std::string fullPath = cl.Get("compare-full");
  vtkSmartPointer<vtkAlgorithm> fullReader;
  if (cl.Has("compare-full") && !(fullReader = MeshReaderFor(fullPath)))
  {
    throw UsageError(
      "--compare-full must name a .ply, .obj, .stl or .vtp file, got '" + fullPath + "'");
  }

  // Everything a user can get wrong is found before the flythrough.
  auto file = std::make_shared<const ModelFile>(ModelFile::Open(settings.ModelPath));
  const bool csvToStdout = cl.Get("csv") == "-";
  std::vector<std::string> inputs{ settings.ModelPath };
  if (fullReader)
  {
    inputs.push_back(fullPath);
  }
  std::optional<PendingFile> csv = csvToStdout ? std::nullopt : Output(cl, "csv", "CSV", inputs);
  std::optional<PendingFile> plot = Output(cl, "plot", "plot", inputs);
  std::optional<PendingFile> image = Output(cl, "image", "image", inputs);
  if (fullReader)
  {
    // VTK's mesh readers crash on some malformed files (a truncated PLY): the builder's own
    // reader checks the input first, naming the file and the problem.
    OpenTriangleSource(fullPath, "");
  }

  const AtpRun atp = FlyAtp(settings, file);
  std::optional<FullRun> full;
  if (fullReader)
  {
    full = FlyFull(settings, fullPath, fullReader, atp);
  }

  if (csv)
  {
    std::ofstream out(csv->PartialPath());
    WriteCsv(out, atp.Seconds, atp.Statistics);
    out.close();
    if (!out)
    {
      throw csv->Failure(std::strerror(errno));
    }
  }
  if (plot)
  {
    WritePng(PlotFlythrough(atp.Seconds, atp.Statistics, full ? full->Seconds : std::vector<double>(),
               plotWidth, plotHeight),
      *plot);
  }
  if (image)
  {
    WritePng(atp.FinalFrame, *image);
  }
  // All or none: a failed output removes the others' partial files.
  for (std::optional<PendingFile>* written : { &csv, &plot, &image })
  {
    if (*written)
    {
      (*written)->Commit();
    }
  }
  if (csvToStdout)
  {
    WriteCsv(std::cout, atp.Seconds, atp.Statistics);
    std::cout.flush();
  }

  FILE* summary = csvToStdout ? stderr : stdout;
  PrintAtpSummary(summary, settings, atp);
  for (const std::optional<PendingFile>* written : { &csv, &plot, &image })
  {
    if (*written)
    {
      std::fprintf(summary, "wrote %s\n", (*written)->Path().c_str());
    }
  }
  if (full)
  {
    PrintComparison(summary, fullPath, atp, *full);
  }
  return 0;
}

}
