// A render window on an EGL device: how the commands draw on a headless GPU machine, with no
// X server at all. Debian's VTK 9.1 is built for X alone (no vtkEGLRenderWindow), so the
// context is made here and handed to VTK's vtkGenericOpenGLRenderWindow.
#ifndef atpEglWindow_h
#define atpEglWindow_h

#include "vtkSmartPointer.h"

#include <string>

class vtkRenderWindow;

namespace atp
{

/// A width x height window drawing into a pbuffer of the first EGL device that gives an
/// OpenGL 3.2 core context (a GPU where the driver offers one; Mesa's software device
/// otherwise). Returns null and says why in `why` when there is none.
vtkSmartPointer<vtkRenderWindow> NewEglWindow(int width, int height, std::string& why);

}

#endif
