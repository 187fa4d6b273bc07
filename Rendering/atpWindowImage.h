// The picture a render window shows, as an image of its own (for comparisons, benchmarks).
#ifndef atpWindowImage_h
#define atpWindowImage_h

#include "vtkATPRenderingModule.h"
#include "vtkSmartPointer.h"

class vtkImageData;
class vtkRenderWindow;

namespace atp
{

/// A copy of the window's back buffer (RGB), detached from any pipeline.
VTKATPRENDERING_EXPORT vtkSmartPointer<vtkImageData> CaptureWindow(vtkRenderWindow* window);

} // namespace atp

#endif
