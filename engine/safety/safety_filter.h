#pragma once

#include "engine/safety/safety_envelope.h"

namespace recon::safety {

/// The envelope applied to one stream of commands: remembers the command in force (for the
/// acceleration rule) and counts what it changed. What a simulated world uses on its own UR5;
/// GuardedArm adds the watchdog and the e-stop around it for a device. Not thread-safe.
class SafetyFilter {
 public:
  /// Throws UserError for invalid limits.
  explicit SafetyFilter(SafetyLimits limits = SafetyLimits{});

  /// Judges `requested_rad_s` for an arm at `q_rad`, `dt_s` after the previous command, and
  /// makes the result the command in force.
  const SafetyDecision& Apply(const JointVector& q_rad, const JointVector& requested_rad_s,
                              double dt_s);
  /// The arm was stopped (a reset, a watchdog, an e-stop): the next command starts from rest.
  void Stopped() { in_force_rad_s_ = {}; }
  /// Counts a command that was replaced by a stop for `reasons` outside the envelope (e-stop).
  void CountStop(uint32_t reasons);

  const JointVector& in_force_rad_s() const { return in_force_rad_s_; }
  const SafetyDecision& last_decision() const { return last_decision_; }
  const SafetyStats& stats() const { return stats_; }
  const SafetyEnvelope& envelope() const { return envelope_; }

 private:
  void Count(uint32_t reasons);

  SafetyEnvelope envelope_;
  JointVector in_force_rad_s_{};
  SafetyDecision last_decision_;
  SafetyStats stats_;
};

}  // namespace recon::safety
