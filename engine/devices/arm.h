#pragma once

#include <array>
#include <string>

namespace recon::devices {

/// The arm's state as the workflow sees it.
struct JointState {
  std::array<double, 6> position_rad{};
  std::array<double, 6> velocity_rad_s{};
  double gripper_opening = 1.0;  ///< 0 closed .. 1 open
  double timestamp_s = 0.0;
};

/// A 6-joint arm under velocity control (UR's speedj): the simulated UR5 or a real one over RTDE.
/// Commands hold until replaced; implementations clamp them to the arm's speed limits and stop
/// the arm when commands stop arriving (a watchdog). Throws UserError when the arm is gone.
class Arm {
 public:
  virtual ~Arm() = default;
  virtual JointState State() const = 0;
  virtual void CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) = 0;
  virtual void CommandGripper(bool close) = 0;
  /// Zero velocity now (a protective stop from the workflow or the safety envelope).
  virtual void Stop() = 0;
  virtual std::string Describe() const = 0;
};

}  // namespace recon::devices
