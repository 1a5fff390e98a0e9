#pragma once

#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "engine/safety/guarded_arm.h"
#include "engine/teach/recorder.h"
#include "engine/worlds/tabletop.h"

namespace recon::teach {

/// What a person's teleop device (keyboard, gamepad) asks of the arm at one moment: a velocity of
/// the grip point in the table frame, the gripper, and whether the demonstration is over.
struct TeleopCommand {
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  /// Turning the wrist about the vertical (rad/s, counter-clockwise seen from above): lines the
  /// fingers' closing axis up with what they are to grasp.
  double wrist_turn_rad_s = 0.0;
  bool close_gripper = false;
  bool finish = false;

  bool operator==(const TeleopCommand& o) const {
    return velocity_m_s == o.velocity_m_s && wrist_turn_rad_s == o.wrist_turn_rad_s &&
           close_gripper == o.close_gripper && finish == o.finish;
  }
};

/// How far a teacher may turn the wrist either way from the home pose's orientation: a parallel
/// gripper is the same turned by half a turn, so a quarter turn each way reaches every grasp.
constexpr double kMaxWristTurn_rad = 1.5707963267948966;
/// The wrist turn's speed under a held key (rad/s): a quarter turn in about 2.6 s.
constexpr double kWristTurnSpeed_rad_s = 0.6;

/// Limits of the Cartesian mapping.
struct CartesianTeleopLimits {
  /// Fastest joint speed sent (the scripted teacher moves at 0.3 rad/s).
  double max_joint_speed_rad_s = 0.6;
  /// The grip point is never driven below this height over the table (the toast is grasped at
  /// about 1 cm): a teleop key held too long must not push the fingers into the table.
  double min_grip_height_m = 0.005;
  double max_grip_height_m = 0.45;
};

/// Where the arm stands and which point of it the teacher steers.
struct TeleopArm {
  /// The UR5's base in the table frame (the simulated cell's is the identity).
  Eigen::Isometry3d base_in_table = Eigen::Isometry3d::Identity();
  /// The steered point along the flange's z axis (the safety envelope's tool point).
  double tool_offset_m = 0.1;
};

/// The arm as its envelope places it: the base where the limits put it, the steered point the
/// envelope's tool point (the simulated cell's base is the table frame's origin).
TeleopArm TeleopArmOf(const safety::SafetyLimits& limits);

/// How far the tool is turned about the vertical from the home pose's orientation (radians,
/// counter-clockwise seen from above, in (-pi, pi]), for an arm at `q_rad` standing as `arm`.
double WristTurn(const std::array<double, 6>& q_rad, const TeleopArm& arm);

/// The one Cartesian teleop of both cells, simulated and real: the action (6 joint velocities,
/// then the gripper, closed above 0.5) that moves the arm's tool point at the commanded table
/// velocity from joints `q_rad`, holding the tool's orientation but for the commanded wrist turn,
/// which stops at kMaxWristTurn_rad either way (resolved rate over the UR5's DH
/// model, damped near singularities, every joint within max_joint_speed_rad_s with the
/// direction kept: resolved_rate.h). The vertical velocity is cut so that one control period
/// (`period_s`) never takes the tool point outside the height limits. Holding still (a zero
/// velocity) sends zero joint velocities, so the arm does not drift while the teacher thinks; so
/// do non-finite commands or joints.
std::vector<float> CartesianTeleopAction(const std::array<double, 6>& q_rad,
                                         const TeleopCommand& command, const TeleopArm& arm,
                                         double period_s, const CartesianTeleopLimits& limits = {});

/// The same for the simulated tabletop's arm (its joints, its envelope's tool point, its base at
/// the table frame's origin, its 10 Hz).
std::vector<float> CartesianTeleopAction(worlds::Tabletop& world, const TeleopCommand& command,
                                         const CartesianTeleopLimits& limits = {});

/// A teacher driven by a person through `*command`, which the caller updates between ticks (the
/// studio's cell thread sets it from the keyboard or the gamepad), for an arm whose joints
/// `joints` reads. `*command` must outlive the teacher; its `finish` ends the demonstration.
Teacher CartesianTeleopTeacher(std::function<std::array<double, 6>()> joints,
                               const TeleopCommand* command, const TeleopArm& arm, double period_s,
                               const CartesianTeleopLimits& limits = {});
/// The same for an arm behind its guard, simulated or real: its joints as the guard reads them,
/// its envelope's base and tool point, commands `period_s` apart.
Teacher CartesianTeleopTeacher(const safety::GuardedArm& arm, const TeleopCommand* command,
                               double period_s, const CartesianTeleopLimits& limits = {});
/// The same for the simulated tabletop's arm (its guarded arm, its 10 Hz).
Teacher CartesianTeleopTeacher(worlds::Tabletop& world, const TeleopCommand* command,
                               const CartesianTeleopLimits& limits = {});

}  // namespace recon::teach
