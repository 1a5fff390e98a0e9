#pragma once

#include <array>

namespace recon::robot {

/// The UR5's tool pose for joint angles `q_rad`, as a controller reports actual_TCP_pose:
/// x, y, z (metres, base frame) and a rotation vector (axis * angle, rad). Standard DH of the
/// UR5 (d1 0.089159, a2 -0.425, a3 -0.39225, d4 0.10915, d5 0.09465, d6 0.0823), no tool offset.
std::array<double, 6> Ur5TcpPose(const std::array<double, 6>& q_rad);

}  // namespace recon::robot
