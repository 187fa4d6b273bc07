#include "atpCalibrate.h"

#include "atpCommandLine.h"
#include "atpCut.h"
#include "atpModelEdit.h"
#include "atpModelFile.h"
#include "atpOffscreenWindow.h"
#include "atpPatchMesh.h"
#include "atpPatchPolyData.h"
#include "atpProgressReport.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>

#include <unistd.h>

namespace atp
{
namespace
{
// The paper's search: the smallest scale with no visible difference, bisected in log space.
constexpr double LowestScale = 1e-3;
constexpr double HighestScale = 1e3;
constexpr int BisectionSteps = 10; // the last bracket spans a factor of 1.014
constexpr double ViewAngleDegrees = 30;
// Eyes range from close-ups just outside the bounding sphere to 4 radii from its centre, where
// the whole model is in the picture (a 30-degree view holds the sphere from 3.9 radii on).
constexpr double NearestRadii = 1.1;
constexpr double FarthestRadii = 4;

/// Uniform in [0, 1) straight from the engine's bits: the std:: distributions are not specified
/// bit for bit, and the views must be the same with every standard library.
double Uniform(std::mt19937_64& random)
{
  return double(random() >> 11) * 0x1.0p-53;
}

/// One random view: what the cut sees (Point) and what the camera needs besides.
struct View
{
  ViewPoint Point;
  double Focus[3];
  double Up[3];
  double ClippingRange[2];
  double Radii; ///< the eye's distance from the model's centre, in bounding radii
};

/// Eyes in uniformly random directions around the bounding sphere, at log-uniform distances
/// (as likely between 1.1 and 2.1 radii as between 2.1 and 4), looking at its centre with a
/// random roll.
std::vector<View> RandomViews(int count, std::uint64_t seed, const ViewPoint& base,
  const double center[3], double radius)
{
  std::mt19937_64 random(seed);
  std::vector<View> views(static_cast<std::size_t>(count));
  for (View& v : views)
  {
    const double z = 2 * Uniform(random) - 1;
    const double phi = 2 * vtkMath::Pi() * Uniform(random);
    const double direction[3] = { std::sqrt(1 - z * z) * std::cos(phi),
      std::sqrt(1 - z * z) * std::sin(phi), z };
    v.Radii = NearestRadii * std::pow(FarthestRadii / NearestRadii, Uniform(random));
    vtkMath::Perpendiculars(direction, v.Up, nullptr, 2 * vtkMath::Pi() * Uniform(random));
    v.Point = base;
    for (int a = 0; a < 3; ++a)
    {
      v.Point.Eye[a] = center[a] + direction[a] * v.Radii * radius;
      v.Focus[a] = center[a];
    }
    v.ClippingRange[0] = (v.Radii - 1) * radius;
    v.ClippingRange[1] = (v.Radii + 1) * radius;
  }
  return views;
}

/// An offscreen window that draws a mesh white on black under the renderer's default headlight
/// and reads the picture back.
class Snapshot
{
public:
  Snapshot(int width, int height)
    : Window(NewOffscreenWindow(width, height))
  {
    Window->SetMultiSamples(0); // one sample per pixel, as the tolerance is stated
    Window->AddRenderer(Renderer);
    Renderer->SetBackground(0, 0, 0);
    Actor->SetMapper(Mapper);
    Actor->GetProperty()->SetColor(1, 1, 1);
    Renderer->AddActor(Actor);
    Capture->SetInput(Window);
    Capture->SetInputBufferTypeToRGB();
    Capture->ReadFrontBufferOff();
  }

  vtkSmartPointer<vtkImageData> Take(vtkPolyData* mesh, const View& view)
  {
    Mapper->SetInputData(mesh);
    vtkCamera* camera = Renderer->GetActiveCamera();
    camera->SetPosition(view.Point.Eye);
    camera->SetFocalPoint(view.Focus);
    camera->SetViewUp(view.Up);
    camera->SetViewAngle(view.Point.ViewAngleDegrees);
    camera->SetClippingRange(view.ClippingRange);
    Window->Render();
    Capture->Modified();
    Capture->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(Capture->GetOutput());
    return image;
  }

private:
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkWindowToImageFilter> Capture;
};

/// What one view shows at one scale.
struct Outcome
{
  std::size_t Triangles = 0;
  double ImageError = 0; ///< vtkImageDifference's thresholded error against the reference
};

/// Compares cuts with the full resolution, view by view.
class Calibrator
{
public:
  Calibrator(const ModelFile& model, std::vector<View> views, int width, int height,
    int intensity, double threshold)
    : Model(model)
    , Selector(model, std::make_shared<const CutIndex>(model))
    , Views(std::move(views))
    , Shot(width, height)
    , Threshold(threshold)
  {
    Difference->SetThreshold(intensity);
    // The reference is every leaf: the input's own triangles as the model stores them
    // (quantized, with the builder's normals), so that only the level of detail differs.
    const PatchMesh full = ExtractCut(model, SelectLevel(model, int(model.Header().Depth)));
    FullTriangles = full.TriangleCount();
    const vtkSmartPointer<vtkPolyData> polyData = PatchMeshToPolyData(full);
    for (const View& v : Views)
    {
      References.push_back(Shot.Take(polyData, v));
    }
  }

  std::size_t ViewCount() const { return Views.size(); }
  const View& GetView(std::size_t v) const { return Views[v]; }
  std::size_t GetFullTriangles() const { return FullTriangles; }
  bool Same(const Outcome& o) const { return o.ImageError <= Threshold; }

  Outcome Evaluate(std::size_t v, double scale)
  {
    Selector.Select(Views[v].Point, scale, ResidentFunction(), Cut);
    const PatchMesh cut = ExtractCut(Model, Cut.Drawn);
    Difference->SetInputData(References[v]);
    Difference->SetImageData(Shot.Take(PatchMeshToPolyData(cut), Views[v]));
    Difference->Update();
    return { cut.TriangleCount(), Difference->GetThresholdedError() };
  }

  /// The smallest scale in [LowestScale, HighestScale] at which view v shows no difference,
  /// within the last bisection step; infinity when even the highest scale shows one. Assumes
  /// a larger scale never looks worse (it only refines the cut further).
  double SmallestScale(std::size_t v)
  {
    if (!Same(Evaluate(v, HighestScale)))
    {
      return std::numeric_limits<double>::infinity();
    }
    if (Same(Evaluate(v, LowestScale)))
    {
      return LowestScale;
    }
    double low = LowestScale, high = HighestScale;
    for (int step = 0; step < BisectionSteps; ++step)
    {
      const double middle = std::sqrt(low * high);
      (Same(Evaluate(v, middle)) ? high : low) = middle;
    }
    return high;
  }

private:
  const ModelFile& Model;
  CutSelector Selector;
  CutResult Cut;
  std::vector<View> Views;
  Snapshot Shot;
  double Threshold;
  std::size_t FullTriangles = 0;
  std::vector<vtkSmartPointer<vtkImageData>> References;
  // vtkTesting's comparison: a pixel may match a neighbour (a one-pixel shift, which the
  // tolerance allows) or a 3x3 average, and only channel differences above the intensity
  // threshold count; the sum of those excesses over the picture (in units of one pixel fully
  // off) is the image error.
  vtkNew<vtkImageDifference> Difference;
};

std::string ScaleFormatNumber(double scale)
{
  if (std::isinf(scale))
  {
    return "> " + FormatNumber(HighestScale);
  }
  if (std::isnan(scale))
  {
    return "-";
  }
  return (scale <= LowestScale ? "<= " : "") + FormatNumber(scale);
}

/// The smallest float not below `scale`: what is stored must not refine less than what passed.
float StoredScale(double scale)
{
  const float stored = float(scale);
  return double(stored) < scale ? std::nextafter(stored, HUGE_VALF) : stored;
}
} // namespace

int CalibrateCommand(const std::vector<std::string>& arguments)
{
  CommandLine cl("calibrate",
    "Finds the model's error scale as the paper does (section 5.2): the smallest scale at which\n"
    "view-dependent cuts at the given tolerance show no visible difference from the full\n"
    "resolution (the model's leaves) in random views, searched by bisection in log space\n"
    "between 0.001 and 1000. The pictures are rendered offscreen (through X, or without a\n"
    "display on an EGL device such as a headless GPU; else run under xvfb-run -a) and\n"
    "compared as VTK's regression tests compare them (vtkImageDifference), with a stricter\n"
    "intensity threshold. See docs/calibration.md.\n"
    "The scale found is stored in MODEL's header; nothing else in the file changes.");
  cl.AddPositional("MODEL", "a .atp model");
  cl.AddOption("views", "", "N", "random views to compare", "12");
  cl.AddOption("size", "", "WxH", "picture size in pixels", "400x300");
  cl.AddOption("tolerance", "", "PX", "screen-space tolerance of the cuts, in pixels", "1");
  cl.AddOption("intensity", "", "N",
    "a color channel differing by more than N (of 255) counts; VTK's tests use 105, which hides "
    "plain shading changes", "32");
  cl.AddOption("threshold", "", "T",
    "largest image error (vtkImageDifference's thresholded error) that is no visible "
    "difference; that of vtkRegressionTestImage", "0.15");
  cl.AddOption("seed", "", "N", "seed of the random views", "1");
  cl.AddOption("check", "", "SCALE",
    "compare the views at SCALE instead of searching; exit code 1 if any differs");
  cl.AddFlag("dry-run", "search and report, but leave MODEL unchanged");
  if (!cl.Parse(arguments))
  {
    return 0;
  }
  const std::string& path = cl.Positional(0);
  const int viewCount = int(cl.GetInteger("views", 1, 1000));
  int width = 0, height = 0;
  cl.GetSize("size", width, height);
  const double tolerance = cl.GetNumber("tolerance", 1e-3, 1e3);
  const int intensity = int(cl.GetInteger("intensity", 0, 255));
  const double threshold = cl.GetNumber("threshold", 0, 1e9);
  const std::uint64_t seed = std::uint64_t(cl.GetInteger("seed", 0, INT64_MAX));
  const bool check = cl.Has("check");
  const double checkScale = check ? cl.GetNumber("check", 0, 1e9) : 0;

  const ModelFile model = ModelFile::Open(path);
  // The scale found is stored in the model: one that cannot be written is said before the search.
  if (!cl.Has("dry-run") && ::access(path.c_str(), W_OK) != 0)
  {
    throw std::runtime_error(path + ": cannot store the scale in it: " + std::strerror(errno) +
      " (--dry-run searches without storing)");
  }
  const ModelHeader& h = model.Header();
  const float previousScale = h.ErrorScale;
  double center[3];
  double radius = 0;
  for (int a = 0; a < 3; ++a)
  {
    center[a] = (h.BoxMin[a] + h.BoxMax[a]) / 2;
    radius += (h.BoxMax[a] - h.BoxMin[a]) * (h.BoxMax[a] - h.BoxMin[a]) / 4;
  }
  radius = std::sqrt(radius);
  ViewPoint base;
  base.ViewAngleDegrees = ViewAngleDegrees;
  base.ViewportHeight = height;
  base.TolerancePixels = tolerance;
  Calibrator calibrator(model, RandomViews(viewCount, seed, base, center, radius), width, height,
    intensity, threshold);

  std::vector<double> smallest(std::size_t(viewCount), std::nan(""));
  double scale = checkScale;
  if (!check)
  {
    ProgressReport progress("calibrating", std::uint64_t(viewCount), "views");
    for (std::size_t v = 0; v < smallest.size(); ++v)
    {
      smallest[v] = calibrator.SmallestScale(v);
      progress.Update(double(v + 1) / double(viewCount));
    }
    progress.Finish();
    scale = StoredScale(*std::max_element(smallest.begin(), smallest.end()));
  }

  std::printf("%s: %d views of %dx%d pixels, tolerance %g px, intensity %d, threshold %g; full "
              "resolution %s triangles\n",
    path.c_str(), viewCount, width, height, tolerance, intensity, threshold,
    FormatCount(double(calibrator.GetFullTriangles())).c_str());
  if (std::isinf(scale))
  {
    const auto worst = std::find(smallest.begin(), smallest.end(), scale) - smallest.begin();
    throw std::runtime_error("view " + std::to_string(worst + 1) +
      " differs from the full resolution even at scale " + FormatNumber(HighestScale) +
      ": the renderer is not deterministic, or --threshold is too strict");
  }
  std::printf("at scale %g:\n%6s %10s %16s %12s %9s %12s\n", scale, "view", "distance",
    "smallest scale", "triangles", "of full", "image error");
  int differing = 0;
  std::size_t least = SIZE_MAX, most = 0;
  double sum = 0;
  for (std::size_t v = 0; v < calibrator.ViewCount(); ++v)
  {
    const Outcome o = calibrator.Evaluate(v, scale);
    const bool same = calibrator.Same(o);
    differing += same ? 0 : 1;
    least = std::min(least, o.Triangles);
    most = std::max(most, o.Triangles);
    sum += double(o.Triangles);
    std::printf("%6zu %8.2f R %16s %12s %8.1f%% %12.3g%s\n", v + 1,
      calibrator.GetView(v).Radii, ScaleFormatNumber(smallest[v]).c_str(),
      FormatCount(double(o.Triangles)).c_str(),
      100.0 * double(o.Triangles) / double(std::max<std::size_t>(1, calibrator.GetFullTriangles())),
      o.ImageError, same ? "" : "  differs");
  }
  std::printf("cuts at scale %g: %s triangles on average (%s to %s), %.1f%% of the %s at full "
              "resolution\n",
    scale, FormatCount(sum / viewCount).c_str(), FormatCount(double(least)).c_str(),
    FormatCount(double(most)).c_str(),
    100.0 * sum / viewCount / double(std::max<std::size_t>(1, calibrator.GetFullTriangles())),
    FormatCount(double(calibrator.GetFullTriangles())).c_str());

  if (check)
  {
    if (differing > 0)
    {
      std::printf("scale %g: visible differences in %d of %d views\n", scale, differing, viewCount);
      return 1;
    }
    std::printf("scale %g: no visible difference in %d views\n", scale, viewCount);
    return 0;
  }
  std::printf("error scale %g: the smallest with no visible difference in every view (the model "
              "has %g)\n",
    scale, double(previousScale));
  if (differing > 0)
  {
    // Bisection assumes that refining never looks worse; say so where a view disagrees.
    std::printf("warning: %d views differ at the scale found although each passed at its own "
                "smallest scale\n",
      differing);
  }
  if (cl.Has("dry-run"))
  {
    std::printf("dry run: %s left unchanged\n", path.c_str());
    return 0;
  }
  SetModelErrorScale(path, float(scale));
  std::printf("stored error scale %g in %s\n", scale, path.c_str());
  return 0;
}

} // namespace atp
