#include "devices/sim/simulated_camera.h"

#include <utility>

#include "devices/sim/scene_lookup.h"
#include "engine/core/error.h"

namespace recon::sim {

SimulatedCamera::SimulatedCamera(worlds::MujocoModel& scene, std::string camera, int width,
                                 int height, std::unique_ptr<worlds::SceneRenderer> renderer,
                                 const devices::Clock& clock)
    : scene_(scene),
      camera_(std::move(camera)),
      width_(width),
      height_(height),
      renderer_(std::move(renderer)),
      clock_(clock) {
  const std::string who = "simulated camera '" + camera_ + "'";
  if (renderer_ == nullptr) throw UserError(who + " needs a scene renderer");
  if (width_ < 1 || height_ < 1) {
    throw UserError(who + ": image size " + std::to_string(width_) + "x" + std::to_string(height_) +
                    " must be at least 1x1 pixels");
  }
  FindCamera(scene_, camera_, who);
}

devices::CameraFrame SimulatedCamera::Capture() {
  devices::CameraFrame frame;
  frame.image = renderer_->Render(scene_, camera_, width_, height_);
  frame.timestamp_s = clock_.NowSeconds();
  // Numbered only once rendered: a failed render is not a lost frame.
  frame.sequence = next_sequence_++;
  return frame;
}

std::string SimulatedCamera::Describe() const {
  return "simulated " + camera_ + " camera " + std::to_string(width_) + "x" +
         std::to_string(height_);
}

}  // namespace recon::sim
