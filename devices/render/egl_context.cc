#include "devices/render/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <cstdio>
#include <mutex>
#include <string_view>
#include <vector>

#include "engine/core/error.h"

namespace recon::render {

std::mutex& PixelReadbackMutex() {
  static std::mutex mutex;
  return mutex;
}

namespace {

std::string EglErrorText(EGLint code) {
  struct Named {
    EGLint code;
    const char* name;
  };
  static constexpr Named kErrors[] = {
      {EGL_SUCCESS, "EGL_SUCCESS"},
      {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"},
      {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"},
      {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},
      {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"},
      {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},
      {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"},
      {EGL_BAD_CURRENT_SURFACE, "EGL_BAD_CURRENT_SURFACE"},
      {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"},
      {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
      {EGL_BAD_NATIVE_PIXMAP, "EGL_BAD_NATIVE_PIXMAP"},
      {EGL_BAD_NATIVE_WINDOW, "EGL_BAD_NATIVE_WINDOW"},
      {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"},
      {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
      {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"},
      {EGL_BAD_DEVICE_EXT, "EGL_BAD_DEVICE_EXT"},
  };
  const char* name = "unknown EGL error";
  for (const Named& error : kErrors) {
    if (error.code == code) name = error.name;
  }
  char hex[16];
  std::snprintf(hex, sizeof(hex), "0x%04X", static_cast<unsigned>(code));
  return std::string(name) + " (" + hex + ")";
}

/// "<call> failed: <EGL error name> (0x....)", reading (and so clearing) EGL's error.
std::string Failure(std::string_view call) {
  return std::string(call) + " failed: " + EglErrorText(eglGetError());
}

bool HasExtension(const char* extensions, std::string_view name) {
  if (extensions == nullptr) return false;
  std::string_view list(extensions);
  for (size_t start = 0; start < list.size();) {
    size_t end = list.find(' ', start);
    if (end == std::string_view::npos) end = list.size();
    if (list.substr(start, end - start) == name) return true;
    start = end + 1;
  }
  return false;
}

// EGL hands out one EGLDisplay per (platform, native display) for the whole process, and
// eglTerminate on it would pull the display out from under every other context on it (say the
// simulated camera's, while the UI's lives on). A display is therefore initialised once and kept
// until the process exits; that also spares each later context re-loading Mesa's driver.
bool InitializeDisplay(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  return eglInitialize(display, &major, &minor) == EGL_TRUE;
}

/// An initialised display and the platform it came from.
struct Display {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string platform;
};

/// Tries the surfaceless platform, then each EGL device; appends what failed to `attempts`.
Display OpenDisplay(std::vector<std::string>& attempts) {
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client_extensions == nullptr) {
    attempts.push_back(Failure("eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS)") +
                       " (libEGL without client extensions: no Mesa EGL installed?)");
    return {};
  }
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!HasExtension(client_extensions, "EGL_EXT_platform_base") ||
      get_platform_display == nullptr) {
    attempts.push_back("EGL lacks EGL_EXT_platform_base (eglGetPlatformDisplayEXT)");
    return {};
  }
  if (HasExtension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
      attempts.push_back(Failure("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)"));
    } else if (!InitializeDisplay(display)) {
      attempts.push_back(Failure("eglInitialize(surfaceless display)"));
    } else {
      return {display, "surfaceless"};
    }
  } else {
    attempts.push_back("EGL lacks EGL_MESA_platform_surfaceless");
  }

  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (!HasExtension(client_extensions, "EGL_EXT_platform_device") || query_devices == nullptr) {
    attempts.push_back("EGL lacks EGL_EXT_platform_device (eglQueryDevicesEXT)");
    return {};
  }
  constexpr EGLint kMaxDevices = 16;
  EGLDeviceEXT devices[kMaxDevices];
  EGLint device_count = 0;
  if (query_devices(kMaxDevices, devices, &device_count) != EGL_TRUE) {
    attempts.push_back(Failure("eglQueryDevicesEXT"));
    return {};
  }
  if (device_count == 0) attempts.push_back("eglQueryDevicesEXT found no EGL device");
  for (EGLint i = 0; i < device_count; ++i) {
    const std::string which = "EGL device " + std::to_string(i);
    EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (display == EGL_NO_DISPLAY) {
      attempts.push_back(
          Failure("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, " + which + ")"));
    } else if (!InitializeDisplay(display)) {
      attempts.push_back(Failure("eglInitialize(" + which + ")"));
    } else {
      return {display, which};
    }
  }
  return {};
}

/// Makes a compatibility-profile desktop GL context on `display`, or returns EGL_NO_CONTEXT and
/// appends why to `attempts`.
EGLContext CreateContext(EGLDisplay display, std::vector<std::string>& attempts) {
  // One attribute-value pair a line.
  // clang-format off
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                      EGL_RED_SIZE, 8,
                                      EGL_GREEN_SIZE, 8,
                                      EGL_BLUE_SIZE, 8,
                                      EGL_ALPHA_SIZE, 8,
                                      EGL_DEPTH_SIZE, 24,
                                      EGL_STENCIL_SIZE, 8,
                                      EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                      EGL_NONE};
  // clang-format on
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  if (eglChooseConfig(display, config_attributes, &config, 1, &config_count) != EGL_TRUE) {
    attempts.push_back(Failure("eglChooseConfig"));
    return EGL_NO_CONTEXT;
  }
  if (config_count == 0) {
    attempts.push_back(
        "eglChooseConfig found no desktop-GL pbuffer config with RGBA8, depth 24, stencil 8");
    return EGL_NO_CONTEXT;
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    attempts.push_back(Failure("eglBindAPI(EGL_OPENGL_API)"));
    return EGL_NO_CONTEXT;
  }
  // MuJoCo 2.2 draws with fixed-function calls and display lists: a core profile will not do.
  const EGLint context_attributes[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) attempts.push_back(Failure("eglCreateContext"));
  return context;
}

std::string Joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& part : parts) out += (out.empty() ? "" : "; ") + part;
  return out;
}

std::string GlString(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text != nullptr ? text : "?";
}

// Contexts are made and destroyed one at a time in the whole process. Mesa's llvmpipe has crashed
// (in swrast_dri.so) while threads made and dropped contexts side by side, and the studio has
// several threads with contexts (window, cell camera, jobs).
std::mutex& ContextLifetimeMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

EglContext::EglContext() {
  std::lock_guard<std::mutex> lifetime(ContextLifetimeMutex());
  std::vector<std::string> attempts;
  const Display display = OpenDisplay(attempts);
  if (display.display == EGL_NO_DISPLAY) {
    throw UserError("cannot create a headless OpenGL context: " + Joined(attempts));
  }
  display_ = display.display;
  EGLContext context = CreateContext(display.display, attempts);
  if (context == EGL_NO_CONTEXT) {
    throw UserError("cannot create a headless OpenGL context on the " + display.platform +
                    " EGL display: " + Joined(attempts));
  }
  context_ = context;
  try {
    // Current only while describing it if the thread already had a context (e.g. the UI's).
    ScopedCurrent current(*this);
    description_ = "EGL " + std::string(eglQueryString(display.display, EGL_VERSION)) + " " +
                   display.platform + "; OpenGL " + GlString(GL_VERSION) + ", " +
                   GlString(GL_RENDERER);
  } catch (const UserError& e) {
    eglDestroyContext(display.display, context);
    throw UserError("cannot use the headless OpenGL context on the " + display.platform +
                    " EGL display: " + e.what());
  }
}

EglContext::~EglContext() {
  std::lock_guard<std::mutex> lifetime(ContextLifetimeMutex());
  // A context current on this thread is only destroyed once released; release it so that no
  // dangling current context remains.
  const EGLenum api = eglQueryAPI();
  eglBindAPI(EGL_OPENGL_API);
  if (IsCurrent()) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglBindAPI(api);
  eglDestroyContext(display_, context_);
}

bool EglContext::IsCurrent() const { return eglGetCurrentContext() == context_; }

void EglContext::MakeCurrent() {
  // eglGetCurrentContext answers for the thread's bound API, which is OpenGL ES by default.
  eglBindAPI(EGL_OPENGL_API);
  if (IsCurrent()) return;
  if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
    throw UserError(Failure("eglMakeCurrent") +
                    " (is the OpenGL context current on another thread?)");
  }
}

ScopedCurrent::ScopedCurrent(EglContext& context) : api_(eglQueryAPI()) {
  // Current contexts are per thread *and per client API*: look at the desktop-GL slot.
  eglBindAPI(EGL_OPENGL_API);
  EGLContext previous = eglGetCurrentContext();
  if (previous != EGL_NO_CONTEXT && !context.IsCurrent()) {
    restore_ = true;
    display_ = eglGetCurrentDisplay();
    draw_ = eglGetCurrentSurface(EGL_DRAW);
    read_ = eglGetCurrentSurface(EGL_READ);
    context_ = previous;
  }
  try {
    context.MakeCurrent();
  } catch (...) {
    eglBindAPI(api_);
    throw;
  }
}

ScopedCurrent::~ScopedCurrent() {
  // Nothing sensible to do if this fails in a destructor; the next user's MakeCurrent reports it.
  if (restore_) eglMakeCurrent(display_, draw_, read_, context_);
  eglBindAPI(api_);
}

}  // namespace recon::render
