#include "engine/safety/ur5_kinematics.h"

#include <cmath>
#include <numbers>

namespace recon::safety {
namespace {

constexpr double kD[6] = {0.089159, 0, 0, 0.10915, 0.09465, 0.0823};
constexpr double kA[6] = {0, -0.425, -0.39225, 0, 0, 0};
constexpr double kAlpha[6] = {std::numbers::pi / 2,  0, 0, std::numbers::pi / 2,
                              -std::numbers::pi / 2, 0};

}  // namespace

Eigen::Isometry3d Ur5FlangePose(const std::array<double, 6>& q_rad) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  for (int i = 0; i < 6; ++i) {
    const double c = std::cos(q_rad[i]), s = std::sin(q_rad[i]);
    const double ca = std::cos(kAlpha[i]), sa = std::sin(kAlpha[i]);
    Eigen::Matrix4d link;
    link << c, -s * ca, s * sa, kA[i] * c,  //
        s, c * ca, -c * sa, kA[i] * s,      //
        0, sa, ca, kD[i],                   //
        0, 0, 0, 1;
    t = t * link;
  }
  Eigen::Isometry3d pose;
  pose.matrix() = t;
  return pose;
}

Eigen::Vector3d Ur5ToolPoint(const std::array<double, 6>& q_rad, double tool_offset_m) {
  const Eigen::Isometry3d flange = Ur5FlangePose(q_rad);
  return flange.translation() + tool_offset_m * flange.linear().col(2);
}

}  // namespace recon::safety
