#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>

namespace recon::safety {

using JointVector = std::array<double, 6>;

/// What the envelope allows an arm to do. The defaults are for teaching with a UR5 (and the
/// simulated one): well under the UR5's own limits (pi rad/s, about 15 rad/s^2), since a person
/// sits next to the arm, yet above what the scripted expert uses (0.3 rad/s, 3 rad/s^2).
struct SafetyLimits {
  JointVector max_velocity_rad_s{1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  JointVector max_acceleration_rad_s2{5.0, 5.0, 5.0, 5.0, 5.0, 5.0};
  /// Joint position limits; a joint may not be driven past them (the UR5's are +-2 pi; the
  /// simulated elbow's +-pi).
  JointVector min_position_rad{-6.2832, -6.2832, -3.1416, -6.2832, -6.2832, -6.2832};
  JointVector max_position_rad{6.2832, 6.2832, 3.1416, 6.2832, 6.2832, 6.2832};
  /// The lowest the tool's working point may go, in the table frame (the table top is z = 0).
  double tool_floor_m = 0.005;
  /// The tool's working point along the flange's z axis (the simulated gripper's finger tips).
  double tool_offset_m = 0.1;
  /// The arm's base in the table frame (the simulated cell puts it at the origin).
  Eigen::Isometry3d base_in_table = Eigen::Isometry3d::Identity();
  /// How far ahead the envelope looks when it checks position limits and the floor: a command
  /// holds until replaced, so it is judged by where it would take the arm within this time.
  double lookahead_s = 0.1;
  /// A command not renewed within this time is replaced by a stop (the watchdog).
  double watchdog_timeout_s = 0.2;

  /// Throws UserError naming the field when a limit is not a positive finite number or a
  /// position range is empty.
  void Validate() const;
};

/// Why a command was changed. Several can apply to one command.
enum SafetyReason : uint32_t {
  kNone = 0,
  kNonFinite = 1u << 0,      ///< NaN or infinity in the command: replaced by a stop
  kVelocity = 1u << 1,       ///< scaled down to the velocity limit
  kAcceleration = 1u << 2,   ///< the change from the previous command was limited
  kPositionLimit = 1u << 3,  ///< a joint would have left its range
  kToolFloor = 1u << 4,      ///< the tool would have gone below the floor
  kEmergencyStop = 1u << 5,  ///< the e-stop is engaged: every command is a stop
  kWatchdog = 1u << 6,       ///< no command arrived in time: the arm was stopped
};

/// Names of the reasons set in `reasons`, e.g. "velocity, tool floor" ("none" when empty).
std::string DescribeReasons(uint32_t reasons);

/// What the envelope made of one command.
struct SafetyDecision {
  JointVector command_rad_s{};  ///< what may be sent to the arm
  uint32_t reasons = kNone;     ///< why it differs from the request (SafetyReason bits)
  double tool_z_m = 0;          ///< the tool's height where the arm is now (table frame)
};

/// Counts of what the envelope has done, for the GUI and the session log.
struct SafetyStats {
  int64_t commands = 0;
  int64_t changed = 0;  ///< commands with any reason set
  int64_t non_finite = 0, velocity = 0, acceleration = 0, position_limit = 0, tool_floor = 0,
          emergency_stop = 0, watchdog = 0;
};

/// The pure part of the safety envelope: judges a joint velocity command against the limits,
/// given where the arm is and what it was last told. No I/O, no clock, no threads, so every rule
/// is tested on exact numbers; GuardedArm applies it to a real or simulated arm.
///
/// Rules, in order: a non-finite command is a stop; the velocity is scaled (keeping its
/// direction) to the per-joint limits; the change from the previous command is scaled to
/// acceleration x dt (slowing down is never limited: stopping must always be possible); a joint
/// heading out of its range is slowed so it stops at the limit within the lookahead; a command
/// that would take the tool below the floor is scaled back until it does not (moving up or along
/// the table is allowed).
class SafetyEnvelope {
 public:
  /// Throws UserError for invalid limits (SafetyLimits::Validate).
  explicit SafetyEnvelope(SafetyLimits limits);

  /// Judges `requested` for an arm at `q_rad` whose previous command was `previous_rad_s`,
  /// given `dt_s` seconds ago (the control period; clamped to [0, lookahead]).
  SafetyDecision Filter(const JointVector& q_rad, const JointVector& previous_rad_s,
                        const JointVector& requested_rad_s, double dt_s) const;

  /// The tool's working point for joint angles `q_rad`, in the table frame.
  Eigen::Vector3d ToolPoint(const JointVector& q_rad) const;
  const SafetyLimits& limits() const { return limits_; }

 private:
  double ToolHeightAfter(const JointVector& q_rad, const JointVector& v, double scale) const;

  SafetyLimits limits_;
};

}  // namespace recon::safety
