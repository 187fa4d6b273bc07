#include "atpEglWindow.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkNew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glew.h>

#include <dlfcn.h>

#include <memory>
#include <vector>

// VTK built for X initialises OpenGL with glewInit(), and GLEW 2.2 built for GLX, having loaded
// every OpenGL entry point, reports failure when no GLX display is current, which is always
// the case under an EGL context. That one outcome means success here: the executable's
// glewInit (exported, see CMakeLists.txt) wraps GLEW's own.
extern "C" GLenum glewInit()
{
  using GlewInit = GLenum (*)();
  static const auto glews = reinterpret_cast<GlewInit>(dlsym(RTLD_NEXT, "glewInit"));
  if (!glews)
  {
    return GLEW_ERROR_NO_GL_VERSION;
  }
  const GLenum result = glews();
  return result == GLEW_ERROR_NO_GLX_DISPLAY ? GLenum(GLEW_OK) : result;
}

namespace atp
{
namespace
{

/// The EGL display, surface and context behind one window; made current whenever VTK asks.
struct EglContext
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLSurface Surface = EGL_NO_SURFACE;
  EGLContext Context = EGL_NO_CONTEXT;

  ~EglContext()
  {
    if (this->Display == EGL_NO_DISPLAY)
    {
      return;
    }
    eglMakeCurrent(this->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (this->Context != EGL_NO_CONTEXT)
    {
      eglDestroyContext(this->Display, this->Context);
    }
    if (this->Surface != EGL_NO_SURFACE)
    {
      eglDestroySurface(this->Display, this->Surface);
    }
    // Not eglTerminate: a device has one EGLDisplay per process, shared by every window on it,
    // and terminating it would take the other windows' contexts along.
  }

  /// Opens `device` and makes a width x height pbuffer with a core context on it.
  bool Open(EGLDeviceEXT device, int width, int height, std::string& why)
  {
    const auto platformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
    this->Display = platformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    EGLint major = 0, minor = 0;
    if (this->Display == EGL_NO_DISPLAY || !eglInitialize(this->Display, &major, &minor))
    {
      this->Display = EGL_NO_DISPLAY;
      why = "the EGL device could not be initialised";
      return false;
    }
    const EGLint configAttributes[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
      EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
      EGL_DEPTH_SIZE, 24, EGL_NONE };
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(this->Display, configAttributes, &config, 1, &configs) || configs < 1)
    {
      why = "the EGL device has no RGBA pbuffer configuration with a depth buffer";
      return false;
    }
    const EGLint surfaceAttributes[] = { EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE };
    this->Surface = eglCreatePbufferSurface(this->Display, config, surfaceAttributes);
    const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION,
      2, EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
    if (this->Surface == EGL_NO_SURFACE || !eglBindAPI(EGL_OPENGL_API) ||
      (this->Context = eglCreateContext(this->Display, config, EGL_NO_CONTEXT,
         contextAttributes)) == EGL_NO_CONTEXT)
    {
      why = "the EGL device gives no OpenGL 3.2 core context on a pbuffer";
      return false;
    }
    return this->MakeCurrent();
  }

  bool MakeCurrent() const
  {
    return eglMakeCurrent(this->Display, this->Surface, this->Surface, this->Context) == EGL_TRUE;
  }
};

/// Answers the generic window's events from its EglContext, and deletes it with the window.
void OnWindowEvent(vtkObject*, unsigned long event, void* clientData, void* callData)
{
  auto* context = static_cast<EglContext*>(clientData);
  if (event == vtkCommand::WindowMakeCurrentEvent)
  {
    context->MakeCurrent();
  }
  else if (event == vtkCommand::WindowIsCurrentEvent)
  {
    *static_cast<bool*>(callData) = eglGetCurrentContext() == context->Context;
  }
}

void DeleteContext(void* clientData)
{
  delete static_cast<EglContext*>(clientData);
}

std::vector<EGLDeviceEXT> Devices(std::string& why)
{
  const auto queryDevices =
    reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (!queryDevices || !eglGetProcAddress("eglGetPlatformDisplayEXT"))
  {
    why = "EGL here cannot enumerate devices (EGL_EXT_device_enumeration)";
    return {};
  }
  EGLint count = 0;
  if (!queryDevices(0, nullptr, &count) || count < 1)
  {
    why = "EGL finds no device";
    return {};
  }
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  queryDevices(count, devices.data(), &count);
  devices.resize(static_cast<std::size_t>(count));
  return devices;
}

}

vtkSmartPointer<vtkRenderWindow> NewEglWindow(int width, int height, std::string& why)
{
  for (EGLDeviceEXT device : Devices(why))
  {
    auto context = std::make_unique<EglContext>();
    if (!context->Open(device, width, height, why))
    {
      continue;
    }
    auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
    vtkNew<vtkCallbackCommand> events;
    events->SetCallback(OnWindowEvent);
    events->SetClientData(context.get());
    events->SetClientDataDeleteCallback(DeleteContext);
    context.release(); // the command owns it now, and outlives the window's own cleanup
    window->AddObserver(vtkCommand::WindowMakeCurrentEvent, events);
    window->AddObserver(vtkCommand::WindowIsCurrentEvent, events);
    window->SetSize(width, height);
    window->SetOffScreenRendering(1);
    window->SetReadyForRendering(true);
    window->SetIsDirect(1);
    window->SetSupportsOpenGL(1);
    if (!window->InitializeFromCurrentContext())
    {
      why = "VTK could not use the EGL device's OpenGL context";
      continue;
    }
    return window;
  }
  return nullptr;
}

}
