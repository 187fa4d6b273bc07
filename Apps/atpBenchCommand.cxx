#include "atpBenchCommand.h"

#include "atpBenchPlot.h"
#include "atpCommandLine.h"
#include "atpFlythrough.h"
#include "atpModelFile.h"
#include "atpPendingFile.h"
#include "atpPngFile.h"
#include "atpProcessMemory.h"
#include "atpProgressReport.h"
#include "atpRenderStatistics.h"
#include "atpTriangleSource.h"
#include "atpVtkErrors.h"
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
#include <memory>
#include <optional>
#include <stdexcept>

namespace atp
{

namespace
{
bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// An offscreen window drawing `actor` with a glossy material (the paper's inspection
/// setting), the same for both mappers so their pictures compare.
vtkSmartPointer<vtkRenderWindow> OffscreenWindow(int width, int height, vtkActor* actor)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
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
  if (EndsWith(path, ".ply"))
  {
    auto reader = vtkSmartPointer<vtkPLYReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  if (EndsWith(path, ".obj"))
  {
    auto reader = vtkSmartPointer<vtkOBJReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  if (EndsWith(path, ".stl"))
  {
    auto reader = vtkSmartPointer<vtkSTLReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
  }
  if (EndsWith(path, ".vtp"))
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

/// An output option's pending file, created now (an unwritable place is reported before the
/// flythrough), or none when the option is not given.
std::optional<PendingFile> Output(const CommandLine& cl, const std::string& option, const std::string& what)
{
  if (!cl.Has(option))
  {
    return std::nullopt;
  }
  return std::make_optional<PendingFile>(cl.Get(option), what);
}
} // namespace

int BenchCommand(const std::vector<std::string>& arguments)
{
  CommandLine cl("bench",
    "Flies the standard path around a model offscreen (a full orbit, zooming from the whole\n"
    "model to a close-up and back, as the paper's figure 7) with vtkATPMapper, timing every\n"
    "frame to completion, and prints per-frame statistics as CSV and a summary. Needs a\n"
    "display (xvfb-run -a without one). With --compare-full, the same path is drawn by\n"
    "vtkPolyDataMapper on the full-resolution mesh, and the summary ends with a line holding\n"
    "speedup=<full median frame time / atp median frame time> and the image difference of\n"
    "the two at the final frame. Output files appear only when complete.");
  cl.AddPositional("MODEL", "a .atp model");
  cl.AddOption("frames", "", "N", "frames of the path", "450");
  cl.AddOption("size", "", "WxH", "window size in pixels", "800x600");
  cl.AddOption("tolerance", "", "PX", "largest screen-space error in pixels", "1");
  cl.AddOption("cache", "", "MiB", "GPU memory for patches", "512");
  cl.AddFlag("no-prefetch", "no speculative prefetching");
  cl.AddOption("csv", "", "FILE",
    "per-frame statistics; '-': standard output, the summary then goes to standard error", "-");
  cl.AddOption("plot", "", "FILE.png", "frame time, triangles, patches and cache misses per frame");
  cl.AddOption("plot-size", "", "WxH", "plot size in pixels", "800x1000");
  cl.AddOption("image", "", "FILE.png", "the final frame, once every patch it needs is drawn");
  cl.AddOption("compare-full", "", "INPUT",
    "the full-resolution mesh (.ply, .obj, .stl, .vtp) to compare with vtkPolyDataMapper");
  cl.AddFlag("quiet", "no progress output");
  if (!cl.Parse(arguments))
  {
    return 0;
  }
  const int frames = int(cl.GetInteger("frames", 2, 1000000));
  int width = 0, height = 0, plotWidth = 0, plotHeight = 0;
  cl.GetSize("size", width, height);
  cl.GetSize("plot-size", plotWidth, plotHeight);
  const double tolerance = cl.GetNumber("tolerance", 1e-3, 1e6);
  const long long cacheMiB = cl.GetInteger("cache", 1, 1 << 24);
  for (const char* option : { "plot", "image" })
  {
    if (cl.Has(option) && !EndsWith(cl.Get(option), ".png"))
    {
      throw UsageError(std::string("--") + option + " must name a .png file, got '" +
        cl.Get(option) + "'");
    }
  }
  const std::string fullPath = cl.Get("compare-full");
  vtkSmartPointer<vtkAlgorithm> fullReader;
  if (cl.Has("compare-full") && !(fullReader = MeshReaderFor(fullPath)))
  {
    throw UsageError("--compare-full must name a .ply, .obj, .stl or .vtp file, got '" + fullPath + "'");
  }
  const std::string modelPath = cl.Positional(0);
  auto file = std::make_shared<const ModelFile>(ModelFile::Open(modelPath));
  const bool csvToStdout = cl.Get("csv") == "-";
  std::optional<PendingFile> csv = csvToStdout ? std::nullopt : Output(cl, "csv", "CSV");
  std::optional<PendingFile> plot = Output(cl, "plot", "plot");
  std::optional<PendingFile> image = Output(cl, "image", "image");
  if (fullReader)
  {
    // VTK's mesh readers crash on some malformed files (a truncated PLY): the builder's own
    // reader checks the input first, before the flythrough, naming the file and the problem.
    OpenTriangleSource(fullPath, "");
  }
  FILE* summary = csvToStdout ? stderr : stdout;

  vtkNew<vtkATPModel> model;
  model->SetModelFile(file);
  vtkNew<vtkATPMapper> mapper;
  FirstVtkError errors;
  errors.Watch(mapper);
  mapper->SetInputData(model);
  mapper->SetTolerancePixels(tolerance);
  mapper->SetCacheBudget(vtkTypeInt64(cacheMiB) << 20);
  mapper->SetPrefetching(!cl.Has("no-prefetch"));
  mapper->ScalarVisibilityOff(); // as the full-resolution mapper: the same pictures
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkSmartPointer<vtkRenderWindow> window = OffscreenWindow(width, height, actor);
  double bounds[6];
  mapper->GetBounds(bounds);
  const double modelMiB = double(std::filesystem::file_size(modelPath)) / 1048576.0;
  const double startMiB = ResidentMiB();

  std::vector<RenderStatistics> statistics;
  ProgressReport progress("atp flythrough", std::uint64_t(frames), "frames");
  const bool quiet = cl.Has("quiet");
  const std::vector<double> seconds = FlyThrough(window, bounds, frames, [&](int f) {
    statistics.push_back(mapper->GetStatistics());
    if (!quiet)
    {
      progress.Update(double(f + 1) / frames);
    }
  });
  progress.Finish();
  const RenderStatistics last = mapper->GetStatistics();
  // The final frame, converged, for the picture and the comparison.
  int extraFrames = 0;
  for (; extraFrames < 200 && !mapper->GetConverged(); ++extraFrames)
  {
    window->Render();
  }
  if (!errors.Message.empty())
  {
    throw std::runtime_error(errors.Message); // a corrupt patch: it names the file and node
  }
  vtkSmartPointer<vtkImageData> atpImage = CaptureWindow(window);
  const double finalMiB = ResidentMiB();
  const double peakMiB = std::max(PeakResidentMiB(), finalMiB); // two counters, sampled apart

  std::vector<double> fullSeconds;
  vtkIdType fullTriangles = 0;
  double imageDifference = 0;
  if (fullReader)
  {
    vtkSmartPointer<vtkPolyData> mesh = ReadFullMesh(fullPath, fullReader);
    fullTriangles = mesh->GetNumberOfPolys();
    vtkNew<vtkPolyDataMapper> fullMapper;
    fullMapper->SetInputData(mesh);
    fullMapper->ScalarVisibilityOff();
    vtkNew<vtkActor> fullActor;
    fullActor->SetMapper(fullMapper);
    vtkSmartPointer<vtkRenderWindow> fullWindow = OffscreenWindow(width, height, fullActor);
    ProgressReport fullProgress("full-resolution flythrough", std::uint64_t(frames), "frames");
    fullSeconds = FlyThrough(fullWindow, bounds, frames, [&](int f) {
      if (!quiet)
      {
        fullProgress.Update(double(f + 1) / frames);
      }
    });
    fullProgress.Finish();
    vtkNew<vtkImageDifference> difference;
    difference->SetInputData(CaptureWindow(fullWindow));
    difference->SetImageData(atpImage);
    difference->SetThreshold(32);
    difference->Update();
    imageDifference = difference->GetThresholdedError();
  }

  if (csv)
  {
    std::ofstream out(csv->PartialPath());
    WriteCsv(out, seconds, statistics);
    out.close();
    if (!out)
    {
      throw csv->Failure(std::strerror(errno));
    }
  }
  if (plot)
  {
    WritePng(PlotFlythrough(seconds, statistics, fullSeconds, plotWidth, plotHeight), *plot);
  }
  if (image)
  {
    WritePng(atpImage, *image);
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
    WriteCsv(std::cout, seconds, statistics);
    std::cout.flush();
  }

  std::vector<double> cut, overhead, patches, triangles;
  double totalTriangles = 0, totalSeconds = 0;
  for (std::size_t f = 0; f < seconds.size(); ++f)
  {
    const RenderStatistics& s = statistics[f];
    cut.push_back(s.CutSeconds);
    overhead.push_back((s.CutSeconds + s.UploadSeconds + s.DrawSeconds) / seconds[f]);
    patches.push_back(double(s.Patches));
    triangles.push_back(double(s.Triangles));
    totalTriangles += double(s.Triangles);
    totalSeconds += seconds[f];
  }
  const double median = Percentile(seconds, 0.5);
  std::fprintf(summary, "model: %s, %.1f MiB, %d frames at %dx%d, tolerance %g px, cache %lld MiB, prefetch %s\n",
    modelPath.c_str(), modelMiB, frames, width, height, tolerance, cacheMiB,
    mapper->GetPrefetching() ? "on" : "off");
  std::fprintf(summary,
    "atp: frame time median %.2f ms, p95 %.2f ms; %.2fM triangles/s; triangles/frame median "
    "%.0f, max %.0f; patches/frame median %.0f, max %.0f\n",
    1e3 * median, 1e3 * Percentile(seconds, 0.95), totalTriangles / totalSeconds / 1e6,
    Percentile(triangles, 0.5), Percentile(triangles, 1.0), Percentile(patches, 0.5),
    Percentile(patches, 1.0));
  std::fprintf(summary,
    "atp: cut %.3f ms median (%.1f%% of the median frame); CPU overhead (cut, uploads, draw "
    "calls) %.1f%% median, %.1f%% p95 of the frame\n",
    1e3 * Percentile(cut, 0.5), 100 * Percentile(cut, 0.5) / median,
    100 * Percentile(overhead, 0.5), 100 * Percentile(overhead, 0.95));
  std::fprintf(summary,
    "atp: decoded %llu patches in %.2f s of background time; cache %.1f MiB, %llu evictions; "
    "prefetch %llu passes, %llu pages advised; final frame converged after %d more frames\n",
    static_cast<unsigned long long>(last.DecodedPatches), last.DecodeSeconds,
    double(last.CacheBytes) / 1048576.0, static_cast<unsigned long long>(last.Evictions),
    static_cast<unsigned long long>(last.PrefetchPasses),
    static_cast<unsigned long long>(last.PrefetchAdvisedPages), extraFrames);
  std::fprintf(summary,
    "atp: resident memory %.1f MiB at start, %.1f MiB at the end (%.2f%% of the model file), "
    "peak %.1f MiB\n",
    startMiB, finalMiB, 100 * finalMiB / modelMiB, peakMiB);
  for (const std::optional<PendingFile>* written : { &csv, &plot, &image })
  {
    if (*written)
    {
      std::fprintf(summary, "wrote %s\n", (*written)->Path().c_str());
    }
  }
  if (fullReader)
  {
    const double fullMedian = Percentile(fullSeconds, 0.5);
    std::fprintf(summary, "full: %s, %lld triangles, frame time median %.2f ms, p95 %.2f ms\n",
      fullPath.c_str(), static_cast<long long>(fullTriangles), 1e3 * fullMedian,
      1e3 * Percentile(fullSeconds, 0.95));
    std::fprintf(summary,
      "speedup=%.2f image_difference=%.4f (vtkImageDifference, intensity threshold 32, final "
      "frame)\n",
      fullMedian / median, imageDifference);
  }
  return 0;
}

}
