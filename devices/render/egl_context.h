#pragma once

#include <mutex>
#include <string>

namespace recon::render {

/// Held while drawing into and reading pixels back from any context of the process: Mesa 22.3's
/// llvmpipe crashed (a segmentation fault inside glReadPixels, swrast_dri.so) about once in a
/// dozen experiments when two threads' contexts read pixels at the same moment on a loaded
/// machine. llvmpipe rasterises each frame on its own worker threads, so little is lost.
std::mutex& PixelReadbackMutex();

/// A desktop OpenGL context without a window or a display server: Mesa's EGL on its surfaceless
/// platform (falling back to an EGL device), compatibility profile, RGBA8 + depth 24 + stencil 8.
/// Whoever uses it renders into their own framebuffer object.
///
/// Knows nothing about MuJoCo, so the headless ImGui screens can use it too. A context is current
/// on one thread at a time: the constructor makes it current on the calling thread (unless that
/// thread already had a desktop-GL context, which it keeps), and each user calls MakeCurrent()
/// or holds a ScopedCurrent while drawing.
class EglContext {
 public:
  /// Creates the context (see above for when it becomes current). Throws UserError naming the EGL
  /// call that failed and its error code (e.g. "eglInitialize failed: EGL_NOT_INITIALIZED
  /// (0x3001)") for every platform tried, when no context can be made.
  EglContext();
  ~EglContext();

  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Makes this context current on the calling thread (a no-op when it already is). Throws
  /// UserError if EGL refuses, typically because the context is current on another thread.
  void MakeCurrent();

  /// Whether this context is the calling thread's current one (for the thread's bound client
  /// API, which MakeCurrent sets to desktop OpenGL).
  bool IsCurrent() const;

  /// How the context was made, for logs and error reports, e.g. "EGL 1.5 surfaceless; OpenGL 4.5
  /// (Compatibility Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& description() const { return description_; }

 private:
  // EGLDisplay and EGLContext are opaque pointers; keeping them as void* keeps <EGL/egl.h> (and
  // its X11-flavoured macros) out of every file that includes this one.
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

/// Makes `context` current for a scope, then gives the thread back the desktop-GL context and the
/// bound client API it had before. When the thread had no context, `context` stays current, so a
/// thread that only renders through one context pays for a single eglMakeCurrent in its life.
class ScopedCurrent {
 public:
  /// Throws UserError like EglContext::MakeCurrent.
  explicit ScopedCurrent(EglContext& context);
  ~ScopedCurrent();

  ScopedCurrent(const ScopedCurrent&) = delete;
  ScopedCurrent& operator=(const ScopedCurrent&) = delete;

 private:
  bool restore_ = false;
  unsigned api_ = 0;
  void* display_ = nullptr;
  void* draw_ = nullptr;
  void* read_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace recon::render
