#include "engine/worlds/simulated_arm.h"

#include <cmath>
#include <sstream>

#include "engine/core/error.h"

namespace recon::worlds {

SimulatedArm::SimulatedArm(Ur5Arm& arm, const devices::Clock& clock, double watchdog_timeout_s)
    : arm_(arm),
      clock_(clock),
      watchdog_timeout_s_(watchdog_timeout_s),
      last_command_s_(clock.NowSeconds()) {
  if (!std::isfinite(watchdog_timeout_s_) || watchdog_timeout_s_ <= 0) {
    throw UserError("the arm watchdog timeout must be a positive number of seconds");
  }
}

bool SimulatedArm::CheckWatchdog() const {
  if (tripped_) return true;
  if (clock_.NowSeconds() - last_command_s_ <= watchdog_timeout_s_) return false;
  bool moving = false;
  for (double v : command_rad_s_) moving |= v != 0.0;
  if (!moving) return false;  // nothing to stop; a resting arm is not a fault
  command_rad_s_ = {};
  arm_.CommandJointVelocities(command_rad_s_);
  tripped_ = true;
  return true;
}

devices::JointState SimulatedArm::State() const {
  CheckWatchdog();
  devices::JointState state;
  state.position_rad = arm_.JointPositions();
  state.velocity_rad_s = arm_.JointVelocities();
  state.gripper_opening = arm_.GripperOpening();
  state.timestamp_s = clock_.NowSeconds();
  return state;
}

void SimulatedArm::CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) {
  // A fresh command renews the watchdog, even after it tripped: a new stream is obeyed.
  command_rad_s_ = velocity_rad_s;
  arm_.CommandJointVelocities(command_rad_s_);
  last_command_s_ = clock_.NowSeconds();
  tripped_ = false;
}

void SimulatedArm::CommandGripper(bool close) {
  CheckWatchdog();
  arm_.CommandGripper(close);
}

void SimulatedArm::Stop() {
  command_rad_s_ = {};
  arm_.CommandJointVelocities(command_rad_s_);
  last_command_s_ = clock_.NowSeconds();
  tripped_ = false;
}

std::string SimulatedArm::Describe() const {
  std::ostringstream out;
  out << "simulated UR5 (watchdog " << watchdog_timeout_s_ << " s)";
  return out.str();
}

}  // namespace recon::worlds
