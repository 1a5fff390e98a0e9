#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "engine/devices/camera.h"
#include "engine/devices/clock.h"
#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/scene_renderer.h"

namespace recon::sim {

/// A camera of a MuJoCo scene as a devices::Camera: each Capture renders the scene as it is now
/// (whoever steps the physics decides when that changes) through a renderer of its own, stamped
/// with the clock's time and the next sequence number. It never blocks: the simulated cell's
/// frame rate is the rate at which it is captured (10 Hz when captured once per control step).
///
/// Holds the scene and the clock by reference: their owner (SimulatedCell) keeps them alive.
/// Like its renderer, bound to the thread that made it.
class SimulatedCamera final : public devices::Camera {
 public:
  /// UserError for a null renderer, a size below 1 pixel, or a camera the scene does not have
  /// (listing the cameras it does have).
  SimulatedCamera(worlds::MujocoModel& scene, std::string camera, int width, int height,
                  std::unique_ptr<worlds::SceneRenderer> renderer, const devices::Clock& clock);

  devices::CameraFrame Capture() override;
  /// E.g. "simulated top camera 64x64".
  std::string Describe() const override;

 private:
  worlds::MujocoModel& scene_;
  std::string camera_;
  int width_, height_;
  std::unique_ptr<worlds::SceneRenderer> renderer_;
  const devices::Clock& clock_;
  int64_t next_sequence_ = 0;
};

}  // namespace recon::sim
