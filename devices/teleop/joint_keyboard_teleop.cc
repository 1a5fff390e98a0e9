#include "devices/teleop/joint_keyboard_teleop.h"

#include <cctype>
#include <cmath>
#include <sstream>

#include "engine/core/error.h"

namespace recon::teleop {

namespace {

// Key pairs (+, -) per joint, base to wrist: the two top letter rows of a QWERTY keyboard.
constexpr char kPlusKeys[] = "qwerty";
constexpr char kMinusKeys[] = "asdfgh";

unsigned char Normalise(char key) {
  return static_cast<unsigned char>(std::tolower(static_cast<unsigned char>(key)));
}

}  // namespace

JointKeyboardTeleop::JointKeyboardTeleop(double speed_rad_s) : speed_rad_s_(speed_rad_s) {
  if (!std::isfinite(speed_rad_s_) || speed_rad_s_ <= 0) {
    throw UserError("the keyboard teleop speed must be a positive number of rad/s");
  }
}

void JointKeyboardTeleop::SetKeyDown(char key, bool down) {
  const unsigned char k = Normalise(key);
  const bool was_down = down_[k];
  down_[k] = down;
  if (!down || was_down) return;  // only a press (an up -> down edge) acts
  if (k == ' ') close_gripper_ = !close_gripper_;
  if (k == '\n' || k == '\r') finished_ = true;
}

devices::TeleopCommand JointKeyboardTeleop::Poll() {
  devices::TeleopCommand command;
  for (int joint = 0; joint < 6; ++joint) {
    const bool plus = down_[static_cast<unsigned char>(kPlusKeys[joint])];
    const bool minus = down_[static_cast<unsigned char>(kMinusKeys[joint])];
    command.joint_velocity_rad_s[joint] =
        (plus ? speed_rad_s_ : 0.0) - (minus ? speed_rad_s_ : 0.0);
  }
  command.close_gripper = close_gripper_;
  command.finished = finished_;
  return command;
}

std::string JointKeyboardTeleop::Describe() const {
  std::ostringstream out;
  out << "joint keyboard teleop (" << speed_rad_s_ << " rad/s)";
  return out.str();
}

void JointKeyboardTeleop::Reset() {
  down_ = {};
  close_gripper_ = false;
  finished_ = false;
}

}  // namespace recon::teleop
