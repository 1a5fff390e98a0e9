#pragma once

#include <mutex>
#include <string>

#include "engine/devices/arm.h"
#include "engine/devices/clock.h"
#include "engine/safety/safety_filter.h"

namespace recon::safety {

/// The limits in a few words, e.g. "1 rad/s, 5 rad/s^2, tool floor 5 mm, watchdog 200 ms".
std::string DescribeLimits(const SafetyLimits& limits);

/// Any arm behind the safety envelope: every velocity command is judged by SafetyEnvelope
/// against the arm's current state before it is passed on; a watchdog stops the arm when
/// commands stop coming; an e-stop, once engaged, turns every command into a stop until it is
/// released. This is what the studio, the recorder and the rollouts hold, for the simulated UR5
/// and for a real one over RTDE alike.
///
/// The watchdog runs when CheckWatchdog() is called: the simulated cell calls it before each
/// physics step (simulated time), and ArmWatchdog calls it every 20 ms on a thread for a real
/// arm. Thread-safe: a watchdog thread, a GUI's e-stop and the control loop may call at once.
/// Holds the arm and the clock by reference; their owner keeps them alive.
class GuardedArm final : public devices::Arm {
 public:
  /// Throws UserError for invalid limits.
  GuardedArm(devices::Arm& arm, SafetyLimits limits, const devices::Clock& clock);

  devices::JointState State() const override;
  /// Judges the command (the envelope), passes on what is allowed, and renews the watchdog.
  /// During an e-stop the arm is stopped instead.
  void CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) override;
  /// Passed on, except during an e-stop (the gripper then keeps its state: a held object is
  /// not dropped).
  void CommandGripper(bool close) override;
  void Stop() override;
  /// The arm's description and the envelope's limits, e.g. "simulated UR5 (...), safety
  /// envelope 1 rad/s, 5 rad/s^2, tool floor 5 mm, watchdog 200 ms".
  std::string Describe() const override;

  /// Stops the arm when the last velocity command is older than the watchdog timeout and was
  /// not already a stop. True if it stopped the arm now. After any stop (this, Stop(), the
  /// e-stop) the next command starts from rest, as the first one does.
  bool CheckWatchdog();
  /// For an arm stepped in whole control periods (a simulated world): commands arrive exactly
  /// `period_s` apart, and the envelope's acceleration rule is applied over whole periods rather
  /// than over differences of clock readings, which carry rounding that would make a long run
  /// differ from a short one in the last bit. UserError unless the period is a positive number.
  void SetCommandPeriod(double period_s);
  /// Stops the arm now and refuses motion until ReleaseEmergencyStop().
  void EngageEmergencyStop(const std::string& reason);
  void ReleaseEmergencyStop();
  bool emergency_stopped() const;
  std::string emergency_stop_reason() const;

  SafetyStats stats() const;
  /// What the envelope made of the last velocity command.
  SafetyDecision last_decision() const;
  const SafetyEnvelope& envelope() const { return filter_.envelope(); }

 private:
  void StopLocked();
  /// The time over which the envelope may change the command in force (SetCommandPeriod).
  double SinceLastCommand(double now) const;

  devices::Arm& arm_;
  const devices::Clock& clock_;
  mutable std::mutex mutex_;
  SafetyFilter filter_;  // its command in force is what the arm was last told
  double last_command_s_ = 0;
  double command_period_s_ = 0;  // 0: commands come when they come (a real arm)
  bool have_command_ = false;    // false after a stop: the next command starts from rest
  bool estop_ = false;
  std::string estop_reason_;
  int64_t watchdog_trips_ = 0;
};

}  // namespace recon::safety
