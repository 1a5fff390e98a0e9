#pragma once

#include "engine/devices/clock.h"
#include "engine/safety/guarded_arm.h"
#include "engine/worlds/simulated_arm.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::worlds {

/// A MuJoCo world's UR5 held as a cell holds its robot: the simulated arm (a devices::Arm that
/// behaves as the UR controller does) behind safety::GuardedArm, on the world's own simulated
/// clock. So every command of the expert, a teacher or a policy passes the same envelope,
/// watchdog and e-stop as on a real UR5, and the studio stops both the same way.
///
/// The world steps it in whole control periods: Command (and the gripper through guard()), then
/// BeforePeriod, the world's physics, AfterPeriod. Commands arrive exactly one period apart, so
/// the guard judges them on the period itself (GuardedArm::SetCommandPeriod): a run is
/// reproduced bit for bit however long the clock has run. Not copyable or movable: the guard
/// holds the arm and the clock by reference.
class GuardedUr5 {
 public:
  /// UserError for invalid limits or a period that is not a positive number of seconds.
  GuardedUr5(Ur5Arm& arm, double control_period_s,
             const safety::SafetyLimits& limits = safety::SafetyLimits{});
  GuardedUr5(const GuardedUr5&) = delete;
  GuardedUr5& operator=(const GuardedUr5&) = delete;

  /// The joint velocities for the next period, as the guard lets them through.
  void Command(const Ur5Joints& velocity_rad_s) { guard_.CommandJointVelocities(velocity_rad_s); }
  /// Before the physics of a period: the watchdogs (the guard's, then the controller's) stop
  /// an arm whose commands stopped coming.
  void BeforePeriod();
  /// After it: simulated time moves on one period.
  void AfterPeriod() { clock_.Advance(period_s_); }
  /// The world placed the arm anew (at rest): the next command starts from rest. An engaged
  /// e-stop stays engaged.
  void Placed() { guard_.Stop(); }

  safety::GuardedArm& guard() { return guard_; }
  const safety::GuardedArm& guard() const { return guard_; }
  const devices::ManualClock& clock() const { return clock_; }
  double period_s() const { return period_s_; }

 private:
  devices::ManualClock clock_;
  SimulatedArm device_;
  safety::GuardedArm guard_;
  double period_s_;
};

}  // namespace recon::worlds
