#include "RenderingFixture.h"

#include "vtkATPMapper.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTesting.h"

#include <chrono>
#include <stdexcept>
#include <thread>
#include <unistd.h>

namespace atp
{
namespace test
{

vtkSmartPointer<vtkRenderWindow> MakeWindow(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  window->AddRenderer(renderer);
  return window;
}

void AimCamera(vtkRenderer* renderer, double azimuth, double elevation, double zoom)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 1);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  camera->Azimuth(azimuth);
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  camera->Dolly(zoom);
  renderer->ResetCameraClippingRange();
}

int RenderUntilConverged(vtkRenderWindow* window, vtkATPMapper* mapper, int frames)
{
  for (int frame = 1; frame <= frames; ++frame)
  {
    window->Render();
    if (mapper->GetConverged())
    {
      return frame;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return frames + 1;
}

double ImageError(vtkImageData* a, vtkImageData* b)
{
  vtkNew<vtkImageDifference> difference;
  difference->SetInputData(a);
  difference->SetImageData(b);
  difference->SetThreshold(StrictIntensityThreshold);
  difference->Update();
  return difference->GetThresholdedError();
}

namespace
{

/// vtkTesting set up to compare with Testing/Data/Baseline/<name>.png, leaving failures in /tmp.
vtkSmartPointer<vtkTesting> BaselineTesting(const std::string& name)
{
  auto testing = vtkSmartPointer<vtkTesting>::New();
  testing->AddArgument("-V");
  const std::string baseline = std::string(ATP_TEST_DATA_DIR) + "/Baseline/" + name + ".png";
  testing->AddArgument(baseline.c_str());
  testing->AddArgument("-T");
  testing->AddArgument("/tmp");
  return testing;
}

}

bool MatchesBaseline(vtkRenderWindow* window, const std::string& name, double threshold, double& error)
{
  vtkSmartPointer<vtkTesting> testing = BaselineTesting(name);
  testing->SetRenderWindow(window);
  const int result = testing->RegressionTest(threshold);
  error = testing->GetImageDifference();
  return result == vtkTesting::PASSED;
}

bool MatchesBaseline(const std::string& png, const std::string& name, double threshold, double& error)
{
  vtkSmartPointer<vtkTesting> testing = BaselineTesting(name);
  const int result = testing->RegressionTest(png, threshold);
  error = testing->GetImageDifference();
  return result == vtkTesting::PASSED;
}

} // namespace test
} // namespace atp
