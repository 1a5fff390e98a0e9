#include "ui/widgets/image_texture.h"

#include <GL/gl.h>

#include <cstdint>

namespace recon::ui {

ImageTexture::~ImageTexture() {
  if (texture_ != 0) glDeleteTextures(1, &texture_);
}

void ImageTexture::Update(const RgbImage& image, uint64_t frame) {
  if (image.width <= 0 || image.height <= 0) return;
  if (frame == frame_ && image.width == width_ && image.height == height_) return;
  if (texture_ == 0) glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  // Nearest: a 64 x 64 policy camera should look like the pixels the policy sees.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE,
               image.rgb.data());
  width_ = image.width;
  height_ = image.height;
  frame_ = frame;
}

void* ImageTexture::id() const {
  return texture_ == 0 ? nullptr : reinterpret_cast<void*>(static_cast<uintptr_t>(texture_));
}

}  // namespace recon::ui
