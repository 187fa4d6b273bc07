// Offscreen render windows for the commands. VTK's X11 window aborts the process when it
// cannot reach an X server, so the display is opened first and its absence is one clear error.
#ifndef atpOffscreenWindow_h
#define atpOffscreenWindow_h

#include "vtkSmartPointer.h"

class vtkRenderWindow;

namespace atp
{

/// Gives `window`, when it draws through X11, the process's connection to the X display,
/// opened on first use and kept open (an X server with no client left resets itself, and
/// refuses connections meanwhile). Throws std::runtime_error saying what to do when there is
/// no display.
void ConnectDisplay(vtkRenderWindow* window);

/// A new offscreen window of width x height pixels, connected to the display.
vtkSmartPointer<vtkRenderWindow> NewOffscreenWindow(int width, int height);

}

#endif
