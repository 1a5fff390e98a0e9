#include "ui/platform/offscreen_target.h"

#include "devices/render/egl_context.h"

// Framebuffer objects are core GL 3.0; GLVND's libOpenGL exports them directly.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "engine/core/error.h"

namespace recon::ui {

OffscreenTarget::OffscreenTarget(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192) {
    throw UserError("window size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is out of range (1 to 8192)");
  }
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glGenRenderbuffers(1, &colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw UserError("the offscreen framebuffer for the studio is incomplete (GL status 0x" + [&] {
      char hex[16];
      std::snprintf(hex, sizeof(hex), "%x", status);
      return std::string(hex);
    }() + ")");
  }
}

OffscreenTarget::~OffscreenTarget() {
  glDeleteRenderbuffers(1, &depth_);
  glDeleteRenderbuffers(1, &colour_);
  glDeleteFramebuffers(1, &framebuffer_);
}

void OffscreenTarget::Bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width_, height_);
}

RgbImage OffscreenTarget::Read() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  RgbImage image;
  image.width = width_;
  image.height = height_;
  image.rgb.resize(static_cast<size_t>(width_) * height_ * 3);
  std::vector<uint8_t> rows(image.rgb.size());
  {
    std::lock_guard lock(render::PixelReadbackMutex());  // see egl_context.h
    glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  }
  const size_t stride = static_cast<size_t>(width_) * 3;
  for (int y = 0; y < height_; ++y) {
    std::memcpy(image.rgb.data() + y * stride, rows.data() + (height_ - 1 - y) * stride, stride);
  }
  return image;
}

}  // namespace recon::ui
