#include "engine/safety/safety_envelope.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/safety/ur5_kinematics.h"

namespace recon::safety {
namespace {

void RequirePositive(double value, const std::string& field) {
  if (!std::isfinite(value) || value <= 0) {
    throw UserError("safety limits: " + field + " must be a positive number of its unit, got " +
                    std::to_string(value));
  }
}

bool AllFinite(const JointVector& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

void SafetyLimits::Validate() const {
  for (int i = 0; i < 6; ++i) {
    const std::string joint = "[" + std::to_string(i) + "]";
    RequirePositive(max_velocity_rad_s[i], "max_velocity_rad_s" + joint);
    RequirePositive(max_acceleration_rad_s2[i], "max_acceleration_rad_s2" + joint);
    if (!std::isfinite(min_position_rad[i]) || !std::isfinite(max_position_rad[i]) ||
        min_position_rad[i] >= max_position_rad[i]) {
      throw UserError("safety limits: joint " + std::to_string(i) +
                      " needs min_position_rad < max_position_rad, got " +
                      std::to_string(min_position_rad[i]) + " and " +
                      std::to_string(max_position_rad[i]));
    }
  }
  if (!std::isfinite(tool_floor_m)) throw UserError("safety limits: tool_floor_m is not finite");
  if (!std::isfinite(tool_offset_m) || tool_offset_m < 0) {
    throw UserError("safety limits: tool_offset_m must be a finite length >= 0");
  }
  if (!base_in_table.matrix().allFinite()) {
    throw UserError("safety limits: base_in_table is not finite");
  }
  RequirePositive(lookahead_s, "lookahead_s");
  RequirePositive(watchdog_timeout_s, "watchdog_timeout_s");
}

std::string DescribeReasons(uint32_t reasons) {
  static const std::pair<SafetyReason, const char*> kNames[] = {{kNonFinite, "non-finite command"},
                                                                {kVelocity, "velocity"},
                                                                {kAcceleration, "acceleration"},
                                                                {kPositionLimit, "joint limit"},
                                                                {kToolFloor, "tool floor"},
                                                                {kEmergencyStop, "e-stop"},
                                                                {kWatchdog, "watchdog"}};
  std::string out;
  for (const auto& [bit, name] : kNames) {
    if ((reasons & bit) == 0) continue;
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out.empty() ? "none" : out;
}

SafetyEnvelope::SafetyEnvelope(SafetyLimits limits) : limits_(std::move(limits)) {
  limits_.Validate();
}

Eigen::Vector3d SafetyEnvelope::ToolPoint(const JointVector& q_rad) const {
  return limits_.base_in_table * Ur5ToolPoint(q_rad, limits_.tool_offset_m);
}

double SafetyEnvelope::ToolHeightAfter(const JointVector& q_rad, const JointVector& v,
                                       double scale) const {
  JointVector q_next;
  for (int i = 0; i < 6; ++i) q_next[i] = q_rad[i] + scale * v[i] * limits_.lookahead_s;
  return ToolPoint(q_next).z();
}

SafetyDecision SafetyEnvelope::Filter(const JointVector& q_rad, const JointVector& previous_rad_s,
                                      const JointVector& requested_rad_s, double dt_s) const {
  SafetyDecision decision;
  if (!AllFinite(q_rad)) {
    // Without a position nothing can be judged: stop.
    decision.reasons = kNonFinite;
    decision.tool_z_m = std::nan("");
    return decision;
  }
  decision.tool_z_m = ToolPoint(q_rad).z();
  if (!AllFinite(requested_rad_s)) {
    decision.reasons = kNonFinite;
    return decision;  // a stop
  }
  JointVector v = requested_rad_s;
  const JointVector previous = AllFinite(previous_rad_s) ? previous_rad_s : JointVector{};

  // Velocity: one scale for all joints keeps the direction the teacher or policy asked for.
  double scale = 1.0;
  for (int i = 0; i < 6; ++i) {
    if (std::abs(v[i]) > limits_.max_velocity_rad_s[i]) {
      scale = std::min(scale, limits_.max_velocity_rad_s[i] / std::abs(v[i]));
    }
  }
  if (scale < 1.0) {
    for (double& x : v) x *= scale;
    decision.reasons |= kVelocity;
  }

  // Acceleration, on the joints that speed up or reverse; braking is always allowed.
  const double dt = std::clamp(std::isfinite(dt_s) ? dt_s : 0.0, 0.0, limits_.lookahead_s);
  double accel_scale = 1.0;
  std::array<bool, 6> limited{};
  for (int i = 0; i < 6; ++i) {
    const bool braking = v[i] * previous[i] >= 0 && std::abs(v[i]) <= std::abs(previous[i]);
    if (braking) continue;
    limited[i] = true;
    const double change = std::abs(v[i] - previous[i]);
    const double allowed = limits_.max_acceleration_rad_s2[i] * dt;
    if (change > allowed) accel_scale = std::min(accel_scale, allowed / change);
  }
  if (accel_scale < 1.0) {
    for (int i = 0; i < 6; ++i) {
      if (limited[i]) v[i] = previous[i] + accel_scale * (v[i] - previous[i]);
    }
    decision.reasons |= kAcceleration;
  }

  // Joint ranges: slow a joint so that it stops at its limit within the lookahead.
  const double h = limits_.lookahead_s;
  for (int i = 0; i < 6; ++i) {
    const double next = q_rad[i] + v[i] * h;
    if (v[i] > 0 && next > limits_.max_position_rad[i]) {
      v[i] = std::max(0.0, (limits_.max_position_rad[i] - q_rad[i]) / h);
      decision.reasons |= kPositionLimit;
    } else if (v[i] < 0 && next < limits_.min_position_rad[i]) {
      v[i] = std::min(0.0, (limits_.min_position_rad[i] - q_rad[i]) / h);
      decision.reasons |= kPositionLimit;
    }
  }

  // The floor: a command that would lower the tool below it is scaled back to where it would
  // just reach it (or, for a tool already below, to where it would not sink further).
  const double z_now = decision.tool_z_m;
  const double z_full = ToolHeightAfter(q_rad, v, 1.0);
  if (z_full < limits_.tool_floor_m && z_full < z_now) {
    const double target = std::min(limits_.tool_floor_m, z_now);
    double lo = 0.0, hi = 1.0;  // z(lo) >= target > z(hi)
    for (int iteration = 0; iteration < 30; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      (ToolHeightAfter(q_rad, v, mid) >= target ? lo : hi) = mid;
    }
    for (double& x : v) x *= lo;
    decision.reasons |= kToolFloor;
  }
  decision.command_rad_s = v;
  return decision;
}

}  // namespace recon::safety
