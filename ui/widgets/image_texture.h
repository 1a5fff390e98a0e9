#pragma once

#include <cstdint>

#include "engine/core/image.h"

namespace recon::ui {

/// An RgbImage as a GL texture ImGui can draw. Re-uploads only when the frame number changes,
/// so a 30 fps camera costs one upload per camera frame, not per UI frame. Main (GL) thread only.
class ImageTexture {
 public:
  ImageTexture() = default;
  ~ImageTexture();
  ImageTexture(const ImageTexture&) = delete;
  ImageTexture& operator=(const ImageTexture&) = delete;

  /// Uploads `image` if `frame` differs from the last upload (or the size changed).
  void Update(const RgbImage& image, uint64_t frame);
  /// For ImGui::Image; null before the first upload.
  void* id() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned texture_ = 0;
  int width_ = 0, height_ = 0;
  uint64_t frame_ = UINT64_MAX;
};

}  // namespace recon::ui
