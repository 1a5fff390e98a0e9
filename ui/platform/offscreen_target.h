#pragma once

#include "engine/core/image.h"

namespace recon::ui {

/// A framebuffer object with an RGBA8 colour buffer and a depth/stencil buffer, on the GL
/// context current at construction; headless frames are drawn into it and read back.
class OffscreenTarget {
 public:
  /// Throws UserError if the framebuffer is incomplete (the message names the GL status).
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  void Bind() const;
  /// The colour buffer, top row first (GL reads bottom-up; this flips).
  RgbImage Read() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  unsigned framebuffer_ = 0, colour_ = 0, depth_ = 0;
};

}  // namespace recon::ui
