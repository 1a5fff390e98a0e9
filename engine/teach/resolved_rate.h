#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

namespace recon::teach {

/// Tuning of the resolved-rate mapping. The defaults suit teaching with a UR5 next to a person.
struct CartesianVelocityOptions {
  /// The tool's working point along the flange's z axis (the two-finger gripper's finger tips).
  double tool_offset_m = 0.1;
  /// The largest damping of the least-squares solve, reached at an exact singularity. Units of
  /// a Jacobian singular value (metres per radian for the linear rows); 0 is a plain inverse.
  double damping = 0.02;
  /// Damping starts when the smallest singular value of the Jacobian falls below this: away from
  /// singularities the solve is exact, so the tool goes where it is told.
  double singular_region = 0.05;
  /// No joint is sent faster than this; a faster solution is scaled as a whole (its direction,
  /// and so the tool's direction, kept). The scripted teacher moves at 0.3 rad/s.
  double max_joint_speed_rad_s = 0.6;
};

/// The UR5's 6 x 6 Jacobian at `q_rad` in the base frame: rows 0-2 map joint velocities to the
/// tool point's linear velocity (m/s), rows 3-5 to the flange's angular velocity (rad/s).
Eigen::Matrix<double, 6, 6> Ur5ToolJacobian(const std::array<double, 6>& q_rad,
                                            double tool_offset_m);

/// Resolved-rate Cartesian teleop for a UR5: the joint velocities (rad/s) that move the tool
/// point at `tool_velocity_table_m_s` (table frame) while holding the tool's orientation, for an
/// arm whose base sits at `base_in_table`. Solved by damped least squares on Ur5ToolJacobian, so
/// the result stays finite (and slow) near singularities, then capped to
/// max_joint_speed_rad_s. A zero velocity gives exactly zero; so does a non-finite velocity or
/// joint angle (a glitching input device must not move the arm).
std::array<double, 6> CartesianJointVelocities(const std::array<double, 6>& q_rad,
                                               const Eigen::Vector3d& tool_velocity_table_m_s,
                                               const Eigen::Isometry3d& base_in_table,
                                               const CartesianVelocityOptions& options = {});
/// The same, turning the tool at `tool_angular_velocity_table_rad_s` (table frame) meanwhile:
/// a teacher turning the wrist about the vertical to line the fingers up with an object.
std::array<double, 6> CartesianJointVelocities(
    const std::array<double, 6>& q_rad, const Eigen::Vector3d& tool_velocity_table_m_s,
    const Eigen::Vector3d& tool_angular_velocity_table_rad_s,
    const Eigen::Isometry3d& base_in_table, const CartesianVelocityOptions& options = {});

}  // namespace recon::teach
