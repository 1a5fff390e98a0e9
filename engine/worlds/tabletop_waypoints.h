#pragma once

// The tabletop's scripted teacher: its waypoints' heights and its tolerances. Internal to the
// world (tabletop.cc, tabletop_expert.cc): Reset's reachability check tries the same waypoints
// the expert drives to, and DemonstrationDone waits for its retreat.

#include <Eigen/Core>

namespace recon::worlds::tabletop_waypoints {

// The expert: waypoints above the toast and the plate, joint steps toward their IK solutions.
inline constexpr double kApproachHeight_m = 0.12;
inline constexpr double kCarryHeight_m = 0.12;
inline constexpr double kLiftFirstBelow_m = 0.08;
inline constexpr double kReleaseHeight_m = 0.05;
inline constexpr double kRetreatHeight_m = 0.25;
inline constexpr double kRetreatTolerance_m = 0.03;
inline constexpr double kAlignTolerance_m = 0.012;
inline constexpr double kDescentTolerance_m = 0.03;
// The expert descends onto the toast as a person at the joystick does: down to the table, not to
// the slice's centre. It aims the tips this far below the centre, i.e. at the safety envelope's
// tool floor (5 mm over the table), which stops them there. Aiming at the centre itself, the
// descent slowed exponentially (the gain, 2.5 /s) just above the window a parallel gripper holds a
// thin slice in (tips at most 3 mm above its centre, Ur5Arm): in the 0.6 s the fingers take it
// got about 0.3 mm inside, and an arm at 80 % of the teacher's speed closed on nothing in every
// layout tried (TabletopProtocolTest; docs/results.md).
inline constexpr double kDescentBelowCentre_m = 0.003;
// It closes once the tips are within this distance of the toast's centre in the plane and this
// height above it: inside the window, with the arm still pushing down into it.
inline constexpr double kGraspTolerance_m = 0.012;
inline constexpr double kCloseHeight_m = 0.002;
inline constexpr double kReleaseTolerance_m = 0.02;
inline constexpr double kExpertGain_per_s = 2.5;
// A teleoperating person is slower than a script: at 0.3 rad/s a demonstration takes about
// 147 steps (14.7 s), close to the paper's 150 samples (16.6 s).
inline constexpr double kExpertMaxSpeed_rad_s = 0.3;

/// Distance in the table's plane.
inline double PlanarDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).head<2>().norm();
}

}  // namespace recon::worlds::tabletop_waypoints
