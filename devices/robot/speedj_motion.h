#pragma once

#include <array>
#include <cstdint>

#include "devices/robot/urscript_command.h"

namespace recon::robot {

/// How a UR controller moves its joints under speedj/stopj, as a fixed-step model for the fake
/// controller: each joint's velocity approaches the commanded one at no more than the command's
/// acceleration, clamped to the UR5's pi rad/s; a speedj expires t seconds after it arrived (the
/// robot then decelerates at the same acceleration), stopj decelerates at its own. A joint past
/// +-`joint_limit_rad` raises a protective stop: everything halts at once and commands are ignored
/// until ClearProtectiveStop().
class SpeedjMotion {
 public:
  static constexpr double kMaxJointSpeed_rad_s = 3.14159265358979;

  SpeedjMotion(const std::array<double, 6>& q_rad, double joint_limit_rad);

  /// Takes a speedj or stopj (other commands are not motion and are ignored) at time `now_s`.
  void Apply(const UrScriptCommand& command, double now_s);
  /// Advances by `dt_s` to `now_s` (the time at the end of the step).
  void Step(double dt_s, double now_s);

  const std::array<double, 6>& q_rad() const { return q_rad_; }
  const std::array<double, 6>& qd_rad_s() const { return qd_rad_s_; }
  /// Puts the joints at `q_rad`, at rest, with no command.
  void Teleport(const std::array<double, 6>& q_rad);
  bool protective_stop() const { return protective_stop_; }
  void ClearProtectiveStop() { protective_stop_ = false; }

 private:
  std::array<double, 6> q_rad_;
  std::array<double, 6> qd_rad_s_{};
  std::array<double, 6> target_rad_s_{};
  double acceleration_rad_s2_ = 1.0;
  double expires_s_ = 0;  // when the speedj times out; infinity for one without t
  double joint_limit_rad_;
  bool protective_stop_ = false;
};

}  // namespace recon::robot
