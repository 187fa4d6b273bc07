// The standard flythrough of the benchmarks: a fixed camera path around a model's bounds (a
// full orbit, zooming to a close-up and back, like the inspection session of the paper's
// figure 7), rendered frame by frame and timed to completion, for any mapper.
#ifndef atpFlythrough_h
#define atpFlythrough_h

#include <functional>
#include <vector>

class vtkRenderWindow;
class vtkRenderer;

namespace atp
{

/// Places the renderer's camera at time t in [0, 1] of the path: a full orbit while zooming
/// from the whole model to a close-up of 1/8 of it at the middle, and back; the elevation
/// sways by 30 degrees.
void PlaceFlythroughCamera(vtkRenderer* renderer, const double bounds[6], double t);

/// Renders `frames` (at least 2) frames of the path in `window` (its first renderer), each
/// timed until the window has finished drawing, and returns the seconds of each. `afterFrame`
/// (optional) runs after each frame with its index, for statistics and progress.
std::vector<double> FlyThrough(vtkRenderWindow* window, const double bounds[6], int frames,
  const std::function<void(int frame)>& afterFrame = {});

/// The value below which a fraction p of `values` lies (0 when empty).
double Percentile(std::vector<double> values, double p);

}

#endif
