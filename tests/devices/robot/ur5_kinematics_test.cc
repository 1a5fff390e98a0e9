// The fake's actual_TCP_pose: the UR5's DH forward kinematics at poses whose answer is known.

#include "devices/robot/ur5_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace recon::robot {
namespace {

TEST(Ur5KinematicsTest, ZeroPoseIsTheArmStretchedAlongMinusX) {
  const std::array<double, 6> p = Ur5TcpPose({0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(p[0], -0.425 - 0.39225, 1e-9);     // a2 + a3
  EXPECT_NEAR(p[1], -(0.10915 + 0.0823), 1e-9);  // -(d4 + d6)
  EXPECT_NEAR(p[2], 0.089159 - 0.09465, 1e-9);   // d1 - d5
  // Tool z along base -y: a quarter turn about x; the rotation vector is (pi/2, 0, 0).
  EXPECT_NEAR(p[3], M_PI / 2, 1e-9);
  EXPECT_NEAR(p[4], 0, 1e-9);
  EXPECT_NEAR(p[5], 0, 1e-9);
}

TEST(Ur5KinematicsTest, TheBaseJointTurnsThePoseAboutZ) {
  const std::array<double, 6> a = Ur5TcpPose({0, -1.0, 1.2, -0.4, 0.3, 0.2});
  const std::array<double, 6> b = Ur5TcpPose({M_PI / 2, -1.0, 1.2, -0.4, 0.3, 0.2});
  EXPECT_NEAR(b[0], -a[1], 1e-9);
  EXPECT_NEAR(b[1], a[0], 1e-9);
  EXPECT_NEAR(b[2], a[2], 1e-9);
  EXPECT_NEAR(std::hypot(a[0], a[1], a[2]), std::hypot(b[0], b[1], b[2]), 1e-9);
}

}  // namespace
}  // namespace recon::robot
