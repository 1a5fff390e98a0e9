#include "engine/safety/guarded_arm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "engine/core/error.h"

namespace recon::safety {
namespace {

bool IsStop(const JointVector& v) {
  for (double x : v) {
    if (x != 0) return false;
  }
  return true;
}

}  // namespace

GuardedArm::GuardedArm(devices::Arm& arm, SafetyLimits limits, const devices::Clock& clock)
    : arm_(arm), clock_(clock), filter_(std::move(limits)) {}

devices::JointState GuardedArm::State() const {
  std::lock_guard lock(mutex_);
  return arm_.State();
}

void GuardedArm::CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) {
  std::lock_guard lock(mutex_);
  if (estop_) {
    filter_.CountStop(kEmergencyStop);
    arm_.Stop();
    return;
  }
  const double now = clock_.NowSeconds();
  const devices::JointState state = arm_.State();
  const double dt = SinceLastCommand(now);
  const SafetyDecision& decision = filter_.Apply(state.position_rad, velocity_rad_s, dt);
  last_command_s_ = now;
  have_command_ = true;
  if (IsStop(decision.command_rad_s)) {
    arm_.Stop();
  } else {
    arm_.CommandJointVelocities(decision.command_rad_s);
  }
}

void GuardedArm::CommandGripper(bool close) {
  std::lock_guard lock(mutex_);
  if (estop_) return;
  arm_.CommandGripper(close);
}

void GuardedArm::Stop() {
  std::lock_guard lock(mutex_);
  StopLocked();
}

void GuardedArm::StopLocked() {
  filter_.Stopped();
  have_command_ = false;  // whatever time passes now, the next command starts from rest
  arm_.Stop();
}

double GuardedArm::SinceLastCommand(double now) const {
  // Before the first command, or after a stop, the arm is at rest: one lookahead's worth of
  // acceleration (one period's, when commands come in periods) is what a command may ask for.
  if (command_period_s_ > 0) {
    if (!have_command_) return command_period_s_;
    return command_period_s_ *
           std::max(1.0, std::round((now - last_command_s_) / command_period_s_));
  }
  return have_command_ ? now - last_command_s_ : filter_.envelope().limits().lookahead_s;
}

void GuardedArm::SetCommandPeriod(double period_s) {
  if (!std::isfinite(period_s) || period_s <= 0) {
    throw UserError("the arm's command period must be a positive number of seconds");
  }
  std::lock_guard lock(mutex_);
  command_period_s_ = period_s;
}

std::string DescribeLimits(const SafetyLimits& l) {
  char text[160];
  std::snprintf(text, sizeof(text),
                "%.3g rad/s, %.3g rad/s^2, tool floor %.0f mm, watchdog %.0f ms",
                l.max_velocity_rad_s[0], l.max_acceleration_rad_s2[0], l.tool_floor_m * 1000,
                l.watchdog_timeout_s * 1000);
  return text;
}

std::string GuardedArm::Describe() const {
  return arm_.Describe() + ", safety envelope " + DescribeLimits(filter_.envelope().limits());
}

bool GuardedArm::CheckWatchdog() {
  std::lock_guard lock(mutex_);
  if (!have_command_ || IsStop(filter_.in_force_rad_s())) return false;
  if (clock_.NowSeconds() - last_command_s_ <= filter_.envelope().limits().watchdog_timeout_s) {
    return false;
  }
  ++watchdog_trips_;
  StopLocked();
  return true;
}

void GuardedArm::EngageEmergencyStop(const std::string& reason) {
  std::lock_guard lock(mutex_);
  estop_ = true;
  estop_reason_ = reason;
  StopLocked();
}

void GuardedArm::ReleaseEmergencyStop() {
  std::lock_guard lock(mutex_);
  estop_ = false;
  estop_reason_.clear();
  have_command_ = false;  // the next command starts from rest
}

bool GuardedArm::emergency_stopped() const {
  std::lock_guard lock(mutex_);
  return estop_;
}

std::string GuardedArm::emergency_stop_reason() const {
  std::lock_guard lock(mutex_);
  return estop_reason_;
}

SafetyStats GuardedArm::stats() const {
  std::lock_guard lock(mutex_);
  SafetyStats stats = filter_.stats();
  stats.watchdog = watchdog_trips_;
  return stats;
}

SafetyDecision GuardedArm::last_decision() const {
  std::lock_guard lock(mutex_);
  return filter_.last_decision();
}

}  // namespace recon::safety
