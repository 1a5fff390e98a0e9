#pragma once

#include <string>

#include "ui/platform/frame_input.h"

struct ImGuiContext;

namespace recon::ui {

/// The ImGui side of a frame: its context, the studio's pinned font and style, and the OpenGL 3
/// backend that draws into whatever framebuffer is bound. Needs a current desktop-GL context
/// (EGL headless or a GLFW window) at construction and for every frame; GL calls happen on that
/// thread only. Frames are deterministic for the same inputs: fixed display size, time step and
/// font, no ini file.
class UiRenderer {
 public:
  struct Options {
    int width = 1280;
    int height = 800;
    float font_size_px = 16.0f;
    /// Everything drawn at this scale (the font, ImGui's paddings and spacings, and the screens'
    /// own sizes through ui::Px): 2 for a high-DPI screen.
    float ui_scale = 1.0f;
  };
  explicit UiRenderer(const Options& options);
  ~UiRenderer();
  UiRenderer(const UiRenderer&) = delete;
  UiRenderer& operator=(const UiRenderer&) = delete;

  /// Starts a frame with this input; ImGui calls may follow until Render().
  void NewFrame(const FrameInput& input);
  /// Finishes the frame and draws it into the bound framebuffer (cleared first).
  void Render();
  /// Draws the last rendered frame again into the bound framebuffer, until the next NewFrame: a
  /// window's back buffer is undefined once swapped, so its screenshots are drawn anew.
  void DrawLastFrame();
  /// The size of the frames from the next NewFrame on, in framebuffer pixels (a resized window).
  /// Throws UserError unless both are positive.
  void Resize(int width, int height);

  int width() const { return options_.width; }
  int height() const { return options_.height; }
  float ui_scale() const { return options_.ui_scale; }
  /// The GL renderer string, for the About box and logs.
  const std::string& gl_description() const { return gl_description_; }

 private:
  Options options_;
  ImGuiContext* context_ = nullptr;
  std::string gl_description_;
  bool mouse_was_down_[3] = {false, false, false};
};

}  // namespace recon::ui
