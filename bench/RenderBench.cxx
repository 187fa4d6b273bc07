// Rendering figures (issue: view-dependent rendering): a fixed flythrough of a model (orbit,
// zoom to a close-up and back) rendered offscreen by vtkATPMapper, per-frame statistics as CSV
// on request, and a summary: median and 95th-percentile frame time, triangles/s, patches per
// frame, the cut's share of the frame, CPU overhead (cut, uploads, draw calls), peak and final
// resident memory against the model's size. With --compare-full MESH, the same path drawn by
// vtkPolyDataMapper on the full-resolution mesh, the speed-up, and the image difference of
// the two at the final frame.
//   atp-bench-render MODEL.atp [--compare-full MESH.ply] [--frames N] [--size WxH]
//                    [--tolerance PX] [--csv FILE] [--no-prefetch]
#include "atpRenderStatistics.h"
#include "atpWindowImage.h"
#include "vtkATPMapper.h"
#include "vtkATPModel.h"
#include "vtkATPReader.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double ResidentMiB()
{
  std::ifstream status("/proc/self/statm");
  long pages = 0, resident = 0;
  status >> pages >> resident;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

double PeakResidentMiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

/// The flythrough at time t in [0, 1]: a full orbit while zooming from the whole model to a
/// close-up of 1/8 of it at the middle, and back; the elevation sways by 30 degrees.
void PlaceCamera(vtkRenderer* renderer, const double bounds[6], double t)
{
  const double center[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const double radius = 0.5 * std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
                                 (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
                                 (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  const double zoom = 1 + 7 * std::sin(M_PI * t) * std::sin(M_PI * t);
  const double distance = radius / std::sin(M_PI / 12) / zoom; // fits the sphere at zoom 1
  const double azimuth = 2 * M_PI * t, elevation = M_PI / 6 * std::sin(2 * M_PI * t);
  // Close-ups look at a point on the bounding sphere, not at the centre inside the model.
  const double focusShift = radius * (1 - 1 / zoom);
  const double direction[3] = { std::cos(elevation) * std::cos(azimuth),
    std::cos(elevation) * std::sin(azimuth), std::sin(elevation) };
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(30);
  camera->SetFocalPoint(center[0] + direction[0] * focusShift, center[1] + direction[1] * focusShift,
    center[2] + direction[2] * focusShift);
  camera->SetPosition(center[0] + direction[0] * (focusShift + distance),
    center[1] + direction[1] * (focusShift + distance), center[2] + direction[2] * (focusShift + distance));
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCameraClippingRange(bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5]);
}

struct Frame
{
  double Seconds;
  atp::RenderStatistics Stats;
};

double Percentile(std::vector<double> values, double p)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0 : values[std::min(values.size() - 1, std::size_t(p * double(values.size())))];
}

vtkSmartPointer<vtkRenderWindow> Window(int width, int height, vtkActor* actor)
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

void Usage()
{
  std::fprintf(stderr, "usage: atp-bench-render MODEL.atp [--compare-full MESH.ply] [--frames N] "
                       "[--size WxH] [--tolerance PX] [--csv FILE] [--no-prefetch]\n");
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    Usage();
    return 2;
  }
  std::string model = argv[1], full, csv;
  int frames = 450, width = 800, height = 600;
  double tolerance = 1;
  bool prefetch = true;
  for (int i = 2; i < argc; ++i)
  {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "--compare-full" && next) { full = argv[++i]; }
    else if (a == "--frames" && next) { frames = std::max(2, std::atoi(argv[++i])); }
    else if (a == "--tolerance" && next) { tolerance = std::atof(argv[++i]); }
    else if (a == "--csv" && next) { csv = argv[++i]; }
    else if (a == "--size" && next && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {}
    else if (a == "--no-prefetch") { prefetch = false; }
    else { Usage(); return 2; }
  }

  vtkNew<vtkATPReader> reader;
  reader->SetFileName(model.c_str());
  reader->Update();
  if (!reader->GetOutput()->GetModelFile())
  {
    return 1; // the reader said why
  }
  vtkNew<vtkATPMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetTolerancePixels(tolerance);
  mapper->SetPrefetching(prefetch);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  auto window = Window(width, height, actor);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  double bounds[6];
  mapper->GetBounds(bounds);
  struct stat st{};
  stat(model.c_str(), &st);
  const double modelMiB = double(st.st_size) / 1048576.0;
  const double startMiB = ResidentMiB();

  std::vector<Frame> log;
  for (int f = 0; f < frames; ++f)
  {
    PlaceCamera(renderer, bounds, double(f) / (frames - 1));
    const Clock::time_point start = Clock::now();
    window->Render();
    window->WaitForCompletion();
    log.push_back({ std::chrono::duration<double>(Clock::now() - start).count(), mapper->GetStatistics() });
  }
  const atp::RenderStatistics last = mapper->GetStatistics();
  // The last frame, converged, for the image comparison.
  for (int f = 0; f < 200 && !mapper->GetConverged(); ++f)
  {
    window->Render();
  }
  vtkSmartPointer<vtkImageData> atpImage = atp::CaptureWindow(window);
  const double finalMiB = ResidentMiB(), peakMiB = PeakResidentMiB();

  if (!csv.empty())
  {
    std::ofstream out(csv);
    out << "frame,seconds,patches,triangles,cache_hits,cache_misses,uploads,upload_bytes,"
           "cache_bytes,cut_seconds,upload_seconds,draw_seconds,converged\n";
    for (std::size_t f = 0; f < log.size(); ++f)
    {
      const atp::RenderStatistics& s = log[f].Stats;
      out << f << ',' << log[f].Seconds << ',' << s.Patches << ',' << s.Triangles << ','
          << s.CacheHits << ',' << s.CacheMisses << ',' << s.Uploads << ',' << s.UploadBytes << ','
          << s.CacheBytes << ',' << s.CutSeconds << ',' << s.UploadSeconds << ',' << s.DrawSeconds
          << ',' << s.Converged << '\n';
    }
  }

  std::vector<double> seconds, cutShare, overheadShare, patches, triangles, cut;
  double totalTriangles = 0, totalSeconds = 0;
  for (const Frame& f : log)
  {
    seconds.push_back(f.Seconds);
    cut.push_back(f.Stats.CutSeconds);
    cutShare.push_back(f.Stats.CutSeconds / f.Seconds);
    overheadShare.push_back((f.Stats.CutSeconds + f.Stats.UploadSeconds + f.Stats.DrawSeconds) / f.Seconds);
    patches.push_back(double(f.Stats.Patches));
    triangles.push_back(double(f.Stats.Triangles));
    totalTriangles += double(f.Stats.Triangles);
    totalSeconds += f.Seconds;
  }
  const double median = Percentile(seconds, 0.5);
  std::printf("model: %s, %.1f MiB, %zu frames at %dx%d, tolerance %g px, prefetch %s\n",
    model.c_str(), modelMiB, log.size(), width, height, tolerance, prefetch ? "on" : "off");
  std::printf("atp: frame time median %.2f ms, p95 %.2f ms; %.2fM triangles/s; triangles/frame "
              "median %.0f, max %.0f; patches/frame median %.0f, max %.0f\n",
    1e3 * median, 1e3 * Percentile(seconds, 0.95), totalTriangles / totalSeconds / 1e6,
    Percentile(triangles, 0.5), Percentile(triangles, 1.0), Percentile(patches, 0.5),
    Percentile(patches, 1.0));
  std::printf("atp: cut %.3f ms median (%.1f%% of the frame); CPU overhead (cut, uploads, draw "
              "calls) %.1f%% median, %.1f%% p95 of the frame\n",
    1e3 * Percentile(cut, 0.5), 100 * Percentile(cutShare, 0.5), 100 * Percentile(overheadShare, 0.5),
    100 * Percentile(overheadShare, 0.95));
  std::printf("atp: decoded %llu patches in %.2f s of background time; cache %.1f MiB, %llu "
              "evictions; prefetch %llu passes, %llu pages advised\n",
    static_cast<unsigned long long>(last.DecodedPatches), last.DecodeSeconds,
    double(last.CacheBytes) / 1048576.0, static_cast<unsigned long long>(last.Evictions),
    static_cast<unsigned long long>(last.PrefetchPasses),
    static_cast<unsigned long long>(last.PrefetchAdvisedPages));
  std::printf("atp: resident memory %.1f MiB at start, %.1f MiB at the end (%.2f%% of the model "
              "file), peak %.1f MiB\n",
    startMiB, finalMiB, 100 * finalMiB / modelMiB, peakMiB);

  if (!full.empty())
  {
    vtkNew<vtkPLYReader> ply;
    ply->SetFileName(full.c_str());
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputConnection(ply->GetOutputPort());
    normals->SplittingOff();
    normals->ConsistencyOff();
    normals->Update();
    vtkNew<vtkPolyDataMapper> fullMapper;
    fullMapper->SetInputConnection(normals->GetOutputPort());
    fullMapper->ScalarVisibilityOff();
    vtkNew<vtkActor> fullActor;
    fullActor->SetMapper(fullMapper);
    auto fullWindow = Window(width, height, fullActor);
    vtkRenderer* fullRenderer = fullWindow->GetRenderers()->GetFirstRenderer();
    std::vector<double> fullSeconds;
    for (int f = 0; f < frames; ++f)
    {
      PlaceCamera(fullRenderer, bounds, double(f) / (frames - 1));
      const Clock::time_point start = Clock::now();
      fullWindow->Render();
      fullWindow->WaitForCompletion();
      fullSeconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    vtkNew<vtkImageDifference> difference;
    difference->SetInputData(atp::CaptureWindow(fullWindow));
    difference->SetImageData(atpImage);
    difference->SetThreshold(32);
    difference->Update();
    const double fullMedian = Percentile(fullSeconds, 0.5);
    std::printf("full: %s, %lld triangles, frame time median %.2f ms, p95 %.2f ms\n", full.c_str(),
      static_cast<long long>(normals->GetOutput()->GetNumberOfPolys()), 1e3 * fullMedian,
      1e3 * Percentile(fullSeconds, 0.95));
    std::printf("speedup=%.2f image_difference=%.4f (vtkImageDifference, intensity threshold 32, "
                "final frame)\n",
      fullMedian / median, difference->GetThresholdedError());
  }
  return 0;
}
