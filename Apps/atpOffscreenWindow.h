// Offscreen render windows for the commands. VTK's X11 window aborts the process when it
// cannot reach an X server, so the display is opened first and its absence is one clear error.
#ifndef atpOffscreenWindow_h
#define atpOffscreenWindow_h

#include "vtkSmartPointer.h"

#include <string>

class vtkRenderWindow;

namespace atp
{

/// A new offscreen window of width x height pixels, connected to the X display (opened on first
/// use and kept open: an X server with no client left resets itself, and refuses connections
/// meanwhile); with no display, drawing on an EGL device (a headless GPU). Throws
/// std::runtime_error saying what to do when neither is there.
vtkSmartPointer<vtkRenderWindow> NewOffscreenWindow(int width, int height);

/// What draws for `window`, once it has rendered: the OpenGL renderer and version strings,
/// such as "NVIDIA H100 80GB HBM3/PCIe/SSE2, OpenGL 4.6.0 NVIDIA 580.159.04".
std::string RendererName(vtkRenderWindow* window);

}

#endif
