#pragma once

#include <array>
#include <string>

#include "engine/devices/arm.h"
#include "engine/devices/clock.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::worlds {

/// The simulated UR5 as a devices::Arm, as its controller behaves: commands go to the Ur5Arm,
/// which clamps them to pi rad/s; the arm does not step physics (its world does, for the whole
/// scene at once). The MuJoCo worlds (Tabletop, BinTransfer) hold it behind safety::GuardedArm,
/// exactly as a real cell holds its robot::UrArm: the envelope, the watchdog and the e-stop are
/// the guard's, for both.
///
/// Its own watchdog models the controller's: a velocity command that is not renewed within
/// `watchdog_timeout_s` of clock time is replaced by zero, as UR's speedj stops when its stream
/// of commands ends. The simulated arm has no thread to notice that on its own, so the check runs
/// whenever someone looks: State(), a gripper command, and CheckWatchdog(), which whoever steps
/// the physics calls first; a velocity command renews it. So a stale command never drives the
/// arm for more than one physics step past the timeout. The gripper keeps its state: a held
/// object is not dropped by a communication gap.
///
/// Holds the arm and the clock by reference; their owner keeps them alive.
class SimulatedArm final : public devices::Arm {
 public:
  static constexpr double kDefaultWatchdogTimeout_s = 0.5;

  /// UserError unless the timeout is a positive number of seconds.
  SimulatedArm(Ur5Arm& arm, const devices::Clock& clock,
               double watchdog_timeout_s = kDefaultWatchdogTimeout_s);

  /// Positions, velocities and gripper from the simulated arm, stamped with the clock. Runs the
  /// watchdog first (hence the mutable state behind a const call).
  devices::JointState State() const override;
  void CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) override;
  void CommandGripper(bool close) override;
  void Stop() override;
  /// E.g. "simulated UR5 (watchdog 0.5 s)".
  std::string Describe() const override;

  /// Zeroes the velocity command if it is older than the timeout. True when the arm is (now)
  /// stopped by the watchdog, until the next velocity command.
  bool CheckWatchdog() const;
  bool watchdog_tripped() const { return tripped_; }
  /// The joint velocities now in force (after the watchdog), as given (before the arm's clamp).
  const Ur5Joints& commanded_velocity_rad_s() const { return command_rad_s_; }
  /// Whether the gripper is commanded closed.
  bool gripper_closed() const { return arm_.GripperClosed(); }
  double watchdog_timeout_s() const { return watchdog_timeout_s_; }

 private:
  Ur5Arm& arm_;
  const devices::Clock& clock_;
  double watchdog_timeout_s_;
  // The watchdog acts from const State(); these are the only state it changes.
  mutable Ur5Joints command_rad_s_{};
  mutable bool tripped_ = false;
  double last_command_s_ = 0.0;
};

}  // namespace recon::worlds
