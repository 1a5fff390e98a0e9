#pragma once

#include <Eigen/Geometry>
#include <array>

namespace recon::safety {

/// The UR5's forward kinematics from its standard DH parameters (REFERENCE.md section 6): the
/// flange pose in the base frame. The simulated arm (assets/mjcf/ur5.xml) is built from the same
/// parameters, and tests/worlds/ur5_arm_test.cc checks the two agree.
Eigen::Isometry3d Ur5FlangePose(const std::array<double, 6>& q_rad);

/// Where the tool's working point is: `tool_offset_m` along the flange's z axis (0.1 m for the
/// two-finger gripper of the simulated cell: the point between the finger tips).
Eigen::Vector3d Ur5ToolPoint(const std::array<double, 6>& q_rad, double tool_offset_m);

}  // namespace recon::safety
