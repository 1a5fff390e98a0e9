#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "engine/core/image.h"
#include "ui/platform/frame_input.h"
#include "ui/platform/ui_renderer.h"

struct GLFWwindow;

namespace recon::ui {

/// The studio on a desktop: a resizable GLFW window with a desktop-GL context, the ImGui renderer
/// drawing into it, and FrameInput filled from the window's events. The screens and the renderer
/// are the ones HeadlessWindow uses; only where input comes from and where pixels go differ.
///
/// GLFW wants windows made, polled and destroyed on the main thread, and keeps process-wide
/// state: one DesktopWindow at a time, on the main thread. Its GL context stays current there.
class DesktopWindow {
 public:
  /// Which API makes the window's GL context. EGL by default: every other context in the process
  /// (MuJoCo cameras, headless windows) is EGL too, and GLVND refuses to make an EGL context
  /// current on a thread that holds a GLX one (eglMakeCurrent: EGL_BAD_ACCESS).
  enum class ContextApi { kEgl, kGlx };

  struct Options {
    std::string title = "RECON Studio";
    UiRenderer::Options renderer;  ///< the window's initial size (resizable later) and font
    ContextApi context_api = ContextApi::kEgl;
    /// When the driver's EGL cannot make a window context, try GLX instead of failing.
    bool fall_back_to_glx = true;
    /// A cap on the frame rate: llvmpipe and Xvfb have no vertical sync, and an uncapped idle
    /// studio would take a core from training. Input wakes a waiting frame at once.
    double max_frames_per_second = 60.0;
    /// Take the UI scale from the screen's content scale (the desktop's DPI setting: 2 on most
    /// high-DPI desktops) instead of renderer.ui_scale, held within [min_ui_scale,
    /// max_ui_scale].
    bool ui_scale_from_screen = false;
    float min_ui_scale = 0.75f;
    float max_ui_scale = 3.0f;
    /// The smallest the window may be made, in pixels at UI scale 1 (times the scale taken);
    /// 0: no limit.
    int min_width = 0, min_height = 0;
  };

  /// Opens the window. Throws UserError naming why when there is no display or GLFW or the GL
  /// context fails (e.g. "cannot open a desktop window: X11: Failed to open display :7"), so the
  /// caller can fall back to a HeadlessWindow.
  explicit DesktopWindow(const Options& options);
  ~DesktopWindow();
  DesktopWindow(const DesktopWindow&) = delete;
  DesktopWindow& operator=(const DesktopWindow&) = delete;

  /// One frame: waits for the next frame's time (or for input), reads the window's events, runs
  /// `draw` (the ImGui calls of the whole window) and shows the result. Returns false, drawing
  /// nothing, once the user has asked to close the window (and the close guard let it).
  bool Frame(const std::function<void()>& draw);
  /// Asked when the window's close button is pressed: true lets the window close, false keeps
  /// it open (the application then asks the person, e.g. whether to stop a training). Without
  /// one the window closes.
  void SetCloseGuard(std::function<bool()> may_close) { may_close_ = std::move(may_close); }

  /// The last frame drawn, top row first, at the window's framebuffer size (empty before the
  /// first frame). The window's back buffer is undefined once swapped, so the frame is drawn
  /// again from ImGui's draw data into an offscreen framebuffer: the same pixels, at no cost to
  /// frames that nobody reads.
  RgbImage Screenshot();

  UiRenderer& renderer() { return *renderer_; }
  /// How the context was made, e.g. "EGL; OpenGL 4.5 (Compatibility Profile) Mesa 22.3.6,
  /// llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& description() const { return description_; }
  /// The scale everything is drawn at (renderer.ui_scale, or the screen's).
  float ui_scale() const;
  /// Frames drawn so far.
  long frames() const { return frames_; }

 private:
  struct Events;  // what GLFW's callbacks collected since the last frame

  FrameInput TakeInput(int window_width, int window_height, int framebuffer_width,
                       int framebuffer_height);

  GLFWwindow* window_ = nullptr;
  std::unique_ptr<Events> events_;
  std::unique_ptr<UiRenderer> renderer_;
  std::function<bool()> may_close_;
  std::string description_;
  double frame_period_s_ = 0;
  double last_frame_s_ = -1;
  long frames_ = 0;
};

}  // namespace recon::ui
