#include "atpOffscreenWindow.h"

#include "atpEglWindow.h"

#include "vtkRenderWindow.h"

#include <X11/Xlib.h>

#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace atp
{

namespace
{
/// Gives an X11 `window` the process's connection to the X display `name`.
void ConnectDisplay(vtkRenderWindow* window, const char* name)
{
  static Display* const display = XOpenDisplay(name); // closed by the exit
  if (!display)
  {
    throw std::runtime_error(std::string("cannot open the X display '") + name +
      "'; without one, run under xvfb-run -a");
  }
  window->SetDisplayId(display);
}
}

vtkSmartPointer<vtkRenderWindow> NewOffscreenWindow(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  // EGL or OSMesa builds of VTK need no X server; Debian's is built for X alone.
  if (window->IsA("vtkXOpenGLRenderWindow"))
  {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display)
    {
      std::string why;
      if (vtkSmartPointer<vtkRenderWindow> headless = NewEglWindow(width, height, why))
      {
        return headless;
      }
      throw std::runtime_error("rendering offscreen needs an X display or an EGL device here (" +
        why + "); without either, run under xvfb-run -a");
    }
    ConnectDisplay(window, display);
  }
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  return window;
}

std::string RendererName(vtkRenderWindow* window)
{
  std::istringstream capabilities(window->ReportCapabilities());
  std::string renderer = "unknown", version = "unknown";
  const auto valueAfter = [](const std::string& line, const std::string& key, std::string& value) {
    if (line.compare(0, key.size(), key) == 0)
    {
      const std::size_t start = line.find_first_not_of(' ', key.size());
      value = start == std::string::npos ? "" : line.substr(start);
    }
  };
  for (std::string line; std::getline(capabilities, line);)
  {
    valueAfter(line, "OpenGL renderer string:", renderer);
    valueAfter(line, "OpenGL version string:", version);
  }
  return renderer + ", OpenGL " + version;
}

}
