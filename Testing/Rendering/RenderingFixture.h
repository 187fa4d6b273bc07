// Shared setup of the rendering tests: one model of the bundled torus, offscreen windows,
// deterministic cameras, and image comparison the way VTK's regression tests compare.
#ifndef atpRenderingFixture_h
#define atpRenderingFixture_h

#include "TestModel.h"

#include "vtkSmartPointer.h"

#include <string>

class vtkATPMapper;
class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;

namespace atp
{
namespace test
{

/// An offscreen window of width x height with one renderer, black background.
vtkSmartPointer<vtkRenderWindow> MakeWindow(int width, int height);
/// Points the renderer's camera at the torus from azimuth/elevation (degrees), `zoom` times
/// closer than the view that fits it.
void AimCamera(vtkRenderer* renderer, double azimuth, double elevation, double zoom);
/// Renders until the mapper drew its whole cut (at most `frames` frames); returns the frames.
int RenderUntilConverged(vtkRenderWindow* window, vtkATPMapper* mapper, int frames = 400);
/// Channel differences below this do not count (vtkImageDifference's default, 105 of 255, lets
/// visibly smoothed surfaces pass; atp calibrate uses 32 too).
constexpr int StrictIntensityThreshold = 32;
/// vtkImageDifference's thresholded error between two pictures (VTK's regression measure),
/// with the strict intensity threshold.
double ImageError(vtkImageData* a, vtkImageData* b);
/// vtkTesting's regression test of the window against Testing/Data/Baseline/<name>.png, with
/// vtkTesting's error in `error`. A failed or missing baseline leaves the picture in /tmp
/// (<name>.png), to inspect or to become the baseline.
bool MatchesBaseline(vtkRenderWindow* window, const std::string& name, double threshold, double& error);
/// The same test for a picture saved as PNG (a screenshot an application wrote).
bool MatchesBaseline(const std::string& png, const std::string& name, double threshold, double& error);

} // namespace test
} // namespace atp

#endif
