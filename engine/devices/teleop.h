#pragma once

#include <array>
#include <string>

namespace recon::devices {

/// What the teacher asks the arm to do at one control step.
struct TeleopCommand {
  std::array<double, 6> joint_velocity_rad_s{};
  bool close_gripper = false;
  bool finished = false;  ///< the teacher ends the demonstration
};

/// A source of teaching commands: the scripted expert (the simulated teacher), a keyboard, or a
/// gamepad. Polled once per control step by the recorder.
class Teleop {
 public:
  virtual ~Teleop() = default;
  virtual TeleopCommand Poll() = 0;
  virtual std::string Describe() const = 0;
};

}  // namespace recon::devices
