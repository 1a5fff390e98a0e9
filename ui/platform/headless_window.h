#pragma once

#include <functional>
#include <memory>

#include "devices/render/egl_context.h"
#include "engine/core/image.h"
#include "ui/platform/frame_input.h"
#include "ui/platform/offscreen_target.h"
#include "ui/platform/ui_renderer.h"

namespace recon::ui {

/// The studio without a display: an EGL context, an offscreen framebuffer of the window's size
/// and the ImGui renderer. Frames are drawn by the same code as in a GLFW window; tests and
/// `recon-studio --headless` read them back as images. Use from one thread.
class HeadlessWindow {
 public:
  /// Throws UserError naming what failed (EGL, framebuffer, ImGui's renderer).
  explicit HeadlessWindow(const UiRenderer::Options& options);
  ~HeadlessWindow();

  /// One frame: `draw` issues the ImGui calls of the whole window.
  void Frame(const FrameInput& input, const std::function<void()>& draw);
  /// The last frame, top row first.
  RgbImage Screenshot();
  UiRenderer& renderer() { return *renderer_; }
  render::EglContext& context() { return context_; }

 private:
  render::EglContext context_;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<UiRenderer> renderer_;
};

}  // namespace recon::ui
