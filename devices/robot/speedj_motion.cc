#include "devices/robot/speedj_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace recon::robot {

SpeedjMotion::SpeedjMotion(const std::array<double, 6>& q_rad, double joint_limit_rad)
    : q_rad_(q_rad), joint_limit_rad_(joint_limit_rad) {}

void SpeedjMotion::Apply(const UrScriptCommand& command, double now_s) {
  if (protective_stop_) return;
  if (command.kind == UrScriptCommand::Kind::kSpeedJ) {
    for (size_t i = 0; i < 6; ++i) {
      target_rad_s_[i] =
          std::clamp(command.velocity_rad_s[i], -kMaxJointSpeed_rad_s, kMaxJointSpeed_rad_s);
    }
    acceleration_rad_s2_ = command.acceleration_rad_s2;
    expires_s_ =
        command.time_s > 0 ? now_s + command.time_s : std::numeric_limits<double>::infinity();
  } else if (command.kind == UrScriptCommand::Kind::kStopJ) {
    target_rad_s_ = {};
    acceleration_rad_s2_ = command.acceleration_rad_s2;
    expires_s_ = now_s;
  }
}

void SpeedjMotion::Step(double dt_s, double now_s) {
  if (protective_stop_) return;
  // The command in force during this step: the speedj if it has not expired at its start.
  const bool expired = now_s - dt_s >= expires_s_;
  const double dv = acceleration_rad_s2_ * dt_s;
  for (size_t i = 0; i < 6; ++i) {
    const double target = expired ? 0.0 : target_rad_s_[i];
    qd_rad_s_[i] += std::clamp(target - qd_rad_s_[i], -dv, dv);
    q_rad_[i] += qd_rad_s_[i] * dt_s;
  }
  for (size_t i = 0; i < 6; ++i) {
    if (std::abs(q_rad_[i]) > joint_limit_rad_) {
      q_rad_[i] = std::clamp(q_rad_[i], -joint_limit_rad_, joint_limit_rad_);
      protective_stop_ = true;
    }
  }
  if (protective_stop_) {
    qd_rad_s_ = {};
    target_rad_s_ = {};
  }
}

void SpeedjMotion::Teleport(const std::array<double, 6>& q_rad) {
  q_rad_ = q_rad;
  qd_rad_s_ = {};
  target_rad_s_ = {};
  expires_s_ = 0;
}

}  // namespace recon::robot
