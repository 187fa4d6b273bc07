#include "atpFlythrough.h"

#include "vtkCamera.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace atp
{

void PlaceFlythroughCamera(vtkRenderer* renderer, const double bounds[6], double t)
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
  camera->SetFocalPoint(center[0] + direction[0] * focusShift,
    center[1] + direction[1] * focusShift, center[2] + direction[2] * focusShift);
  camera->SetPosition(center[0] + direction[0] * (focusShift + distance),
    center[1] + direction[1] * (focusShift + distance),
    center[2] + direction[2] * (focusShift + distance));
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCameraClippingRange(
    bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5]);
}

std::vector<double> FlyThrough(vtkRenderWindow* window, const double bounds[6], int frames,
  const std::function<void(int frame)>& afterFrame)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  std::vector<double> seconds;
  seconds.reserve(std::size_t(frames));
  for (int f = 0; f < frames; ++f)
  {
    PlaceFlythroughCamera(renderer, bounds, double(f) / (frames - 1));
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (afterFrame)
    {
      afterFrame(f);
    }
  }
  return seconds;
}

double Percentile(std::vector<double> values, double p)
{
  std::sort(values.begin(), values.end());
  return values.empty()
    ? 0
    : values[std::min(values.size() - 1, std::size_t(p * double(values.size())))];
}

}
