#include "devices/sim/simulated_cell.h"

#include <vector>

#include "devices/sim/hidden_uwb_frame.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::sim {

namespace {

// Seed streams of the installation: the same streams as the simulated calibration procedure.
constexpr uint64_t kFrameStream = 1, kUwbStream = 3;

std::unique_ptr<worlds::SceneRenderer> MakeRenderer(const worlds::SceneRendererFactory& factory) {
  if (!factory) throw UserError("the simulated cell needs a scene renderer factory");
  return factory();
}

}  // namespace

SimulatedCell::SimulatedCell(const SimulatedCellOptions& options,
                             const worlds::SceneRendererFactory& renderer_factory) {
  Rng frame_rng(Rng::Derive(options.seed, kFrameStream));
  hidden_table_to_uwb_ = DrawHiddenUwbFrame(frame_rng);
  world_ = std::make_unique<worlds::Tabletop>(options.tabletop, MakeRenderer(renderer_factory));
  camera_ = std::make_unique<SimulatedCamera>(
      world_->scene(), kCamera, options.tabletop.image_width, options.tabletop.image_height,
      MakeRenderer(renderer_factory), world_->clock());
  SimulatedBeacon plate{kBeaconName, kBeaconSite, {}};
  plate.dwm.table_to_uwb = hidden_table_to_uwb_;
  plate.dwm.seed = Rng::Derive(options.seed, kUwbStream);
  std::vector<SimulatedBeacon> beacons;
  beacons.push_back(std::move(plate));
  beacons_ =
      std::make_unique<SimulatedBeaconSource>(world_->scene(), std::move(beacons), world_->clock());
}

void SimulatedCell::Reset(uint64_t seed) { world_->Reset(seed); }  // also stops the arm

void SimulatedCell::Step(const devices::TeleopCommand& command) {
  // Tabletop::Step is the world's one way to command and step it: the same guarded arm a
  // recorder or a policy drives.
  std::vector<float> u(worlds::Ur5Arm::kJoints + 1);
  for (int i = 0; i < worlds::Ur5Arm::kJoints; ++i) {
    u[i] = static_cast<float>(command.joint_velocity_rad_s[i]);
  }
  u[worlds::Ur5Arm::kJoints] = command.close_gripper ? 1.0f : 0.0f;
  world_->Step(u);
}

}  // namespace recon::sim
