#include "ui/platform/headless_window.h"

namespace recon::ui {

HeadlessWindow::HeadlessWindow(const UiRenderer::Options& options) {
  context_.MakeCurrent();
  target_ = std::make_unique<OffscreenTarget>(options.width, options.height);
  target_->Bind();
  renderer_ = std::make_unique<UiRenderer>(options);
}

HeadlessWindow::~HeadlessWindow() {
  context_.MakeCurrent();  // the renderer and framebuffer free GL objects of this context
  renderer_.reset();
  target_.reset();
}

void HeadlessWindow::Frame(const FrameInput& input, const std::function<void()>& draw) {
  context_.MakeCurrent();
  renderer_->NewFrame(input);
  draw();
  target_->Bind();
  renderer_->Render();
}

RgbImage HeadlessWindow::Screenshot() {
  context_.MakeCurrent();
  return target_->Read();
}

}  // namespace recon::ui
