#pragma once

#include <array>
#include <string>

#include "engine/devices/teleop.h"

namespace recon::teleop {

/// Joint-space teaching from a keyboard (the studio's keyboard teleop is Cartesian: arrows move
/// the grip point as the camera shows it; this one drives each joint on its own, for a terminal
/// or for moving the arm out of a corner): the caller reports key presses and releases through
/// SetKeyDown, and each Poll turns the keys held now into a command. Letters are case-insensitive
/// (Shift changes nothing).
///
///   joint      +   -
///   1 (base)   q   a
///   2          w   s
///   3          e   d
///   4          r   f
///   5          t   g
///   6          y   h
///
/// A held key drives its joint at the configured speed (both keys of a joint cancel out).
/// Space toggles the gripper (closed <-> open) on each press, counted when it happens, so a tap
/// between two polls is not lost and holding it does not repeat. Enter ('\n' or '\r') finishes the
/// demonstration: every later Poll reports `finished` until Reset. Other keys are ignored.
class JointKeyboardTeleop final : public devices::Teleop {
 public:
  static constexpr double kDefaultSpeed_rad_s = 0.5;

  /// UserError unless the speed is a positive number of rad/s.
  explicit JointKeyboardTeleop(double speed_rad_s = kDefaultSpeed_rad_s);

  void SetKeyDown(char key, bool down);
  devices::TeleopCommand Poll() override;
  /// E.g. "joint keyboard teleop (0.5 rad/s)".
  std::string Describe() const override;

  /// Releases every key, opens the gripper and clears `finished`: ready for a new demonstration.
  void Reset();

 private:
  std::array<bool, 256> down_{};
  bool close_gripper_ = false;
  bool finished_ = false;
  double speed_rad_s_;
};

}  // namespace recon::teleop
