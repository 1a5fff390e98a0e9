#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/teach/recorder.h"
#include "engine/worlds/tabletop.h"

namespace recon::teach {

/// What a person's teleop device (keyboard, gamepad) asks of the arm at one moment: a velocity of
/// the grip point in the table frame, the gripper, and whether the demonstration is over.
struct TeleopCommand {
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  bool close_gripper = false;
  bool finish = false;

  bool operator==(const TeleopCommand& o) const {
    return velocity_m_s == o.velocity_m_s && close_gripper == o.close_gripper && finish == o.finish;
  }
};

/// Limits of the Cartesian mapping.
struct CartesianTeleopLimits {
  /// Fastest joint speed sent (the scripted teacher moves at 0.3 rad/s).
  double max_joint_speed_rad_s = 0.6;
  /// The grip point is never driven below this height over the table (the toast is grasped at
  /// about 1 cm): a teleop key held too long must not push the fingers into the table.
  double min_grip_height_m = 0.005;
  double max_grip_height_m = 0.45;
};

/// The tabletop arm's action for a teleop command: joint velocities that move the grip point by
/// one control period of the commanded velocity, the tool pointing straight down (the arm's IK),
/// and the gripper as commanded. Holding still (zero velocity) sends zero joint velocities, so
/// the arm does not drift while the teacher thinks. A target out of reach also holds still.
std::vector<float> CartesianTeleopAction(worlds::Tabletop& world, const TeleopCommand& command,
                                         const CartesianTeleopLimits& limits = {});

/// A teacher driven by a person through `*command`, which the caller updates between ticks (the
/// studio's cell thread sets it from the keyboard or the gamepad). `*command` must outlive the
/// teacher; its `finish` ends the demonstration.
Teacher CartesianTeleopTeacher(worlds::Tabletop& world, const TeleopCommand* command,
                               const CartesianTeleopLimits& limits = {});

}  // namespace recon::teach
