#include "devices/sim/scripted_teleop.h"

#include <vector>

#include "engine/core/error.h"

namespace recon::sim {

namespace {

constexpr int kJoints = 6;

}  // namespace

ScriptedTeleop::ScriptedTeleop(worlds::World& world) : world_(world) {}

devices::TeleopCommand ScriptedTeleop::Poll() {
  devices::TeleopCommand command;
  if (polls_ >= world_.EpisodeLength()) {
    command.finished = true;
    return command;
  }
  const std::vector<float> u = world_.ExpertAction();
  if (static_cast<int>(u.size()) != kJoints + 1) {
    throw UserError(
        "the scripted teleop drives a 6-joint arm and its gripper (7 action values); "
        "the " +
        world_.Name() + " expert gives " + std::to_string(u.size()));
  }
  for (int i = 0; i < kJoints; ++i) command.joint_velocity_rad_s[i] = u[i];
  command.close_gripper = u[kJoints] > 0.5f;
  ++polls_;
  return command;
}

std::string ScriptedTeleop::Describe() const { return "scripted expert of " + world_.Name(); }

}  // namespace recon::sim
