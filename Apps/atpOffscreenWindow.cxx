#include "atpOffscreenWindow.h"

#include "vtkRenderWindow.h"

#include <X11/Xlib.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace atp
{

void ConnectDisplay(vtkRenderWindow* window)
{
  if (!window->IsA("vtkXOpenGLRenderWindow"))
  {
    return; // EGL or OSMesa builds of VTK need no X server
  }
  const char* name = std::getenv("DISPLAY");
  if (!name || !*name)
  {
    throw std::runtime_error(
      "rendering offscreen needs an X display here; without one, run under xvfb-run -a");
  }
  static Display* const display = XOpenDisplay(name); // closed by the exit
  if (!display)
  {
    throw std::runtime_error(std::string("cannot open the X display '") + name +
      "'; without one, run under xvfb-run -a");
  }
  window->SetDisplayId(display);
}

vtkSmartPointer<vtkRenderWindow> NewOffscreenWindow(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  ConnectDisplay(window);
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  return window;
}

}
