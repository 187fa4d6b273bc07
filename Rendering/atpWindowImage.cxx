#include "atpWindowImage.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkWindowToImageFilter.h"

namespace atp
{

vtkSmartPointer<vtkImageData> CaptureWindow(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  capture->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(capture->GetOutput());
  return image;
}

} // namespace atp
