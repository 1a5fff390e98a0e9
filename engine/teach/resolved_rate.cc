#include "engine/teach/resolved_rate.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/safety/ur5_kinematics.h"

namespace recon::teach {

namespace {

using Joints = std::array<double, 6>;

bool AllFinite(const Joints& q) {
  return std::all_of(q.begin(), q.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

Eigen::Matrix<double, 6, 6> Ur5ToolJacobian(const Joints& q_rad, double tool_offset_m) {
  // Central differences of the forward kinematics rather than an analytic Jacobian: it reuses
  // the one DH model the safety envelope and the simulated arm are checked against, so the
  // teleop cannot drift from them. Twelve 4x4 products cost microseconds; the step keeps the
  // truncation error (h^2) and the round-off (eps / h) both near 1e-10.
  constexpr double kStep_rad = 1e-5;
  Eigen::Matrix<double, 6, 6> jacobian;
  for (int i = 0; i < 6; ++i) {
    Joints plus = q_rad, minus = q_rad;
    plus[i] += kStep_rad;
    minus[i] -= kStep_rad;
    const Eigen::Isometry3d pose_plus = safety::Ur5FlangePose(plus);
    const Eigen::Isometry3d pose_minus = safety::Ur5FlangePose(minus);
    const Eigen::Vector3d tool_plus =
        pose_plus.translation() + tool_offset_m * pose_plus.linear().col(2);
    const Eigen::Vector3d tool_minus =
        pose_minus.translation() + tool_offset_m * pose_minus.linear().col(2);
    jacobian.block<3, 1>(0, i) = (tool_plus - tool_minus) / (2 * kStep_rad);
    // The rotation from one side to the other, as an axis-angle vector in the base frame.
    const Eigen::AngleAxisd turn(pose_plus.linear() * pose_minus.linear().transpose());
    jacobian.block<3, 1>(3, i) = turn.angle() * turn.axis() / (2 * kStep_rad);
  }
  return jacobian;
}

Joints CartesianJointVelocities(const Joints& q_rad, const Eigen::Vector3d& tool_velocity_table_m_s,
                                const Eigen::Isometry3d& base_in_table,
                                const CartesianVelocityOptions& options) {
  return CartesianJointVelocities(q_rad, tool_velocity_table_m_s, Eigen::Vector3d::Zero(),
                                  base_in_table, options);
}

Joints CartesianJointVelocities(const Joints& q_rad, const Eigen::Vector3d& tool_velocity_table_m_s,
                                const Eigen::Vector3d& tool_angular_velocity_table_rad_s,
                                const Eigen::Isometry3d& base_in_table,
                                const CartesianVelocityOptions& options) {
  if (!(options.damping >= 0) || !(options.singular_region > 0) ||
      !(options.max_joint_speed_rad_s > 0) || !std::isfinite(options.tool_offset_m)) {
    throw std::invalid_argument(
        "CartesianVelocityOptions: damping must be >= 0, singular_region and "
        "max_joint_speed_rad_s > 0, tool_offset_m finite");
  }
  Joints qd{};
  if (!tool_velocity_table_m_s.allFinite() || !tool_angular_velocity_table_rad_s.allFinite() ||
      !AllFinite(q_rad) ||
      (tool_velocity_table_m_s.isZero(0.0) && tool_angular_velocity_table_rad_s.isZero(0.0))) {
    return qd;
  }
  Eigen::Matrix<double, 6, 1> twist;
  twist << base_in_table.linear().transpose() * tool_velocity_table_m_s,
      base_in_table.linear().transpose() * tool_angular_velocity_table_rad_s;

  const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(
      Ur5ToolJacobian(q_rad, options.tool_offset_m), Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix<double, 6, 1>& sigma = svd.singularValues();
  // Damping that fades in only inside the singular region (Maciejewski & Klein): a constant
  // damping would shorten every motion a little, and the teacher would see the tool lag.
  const double smallest = sigma(5);
  const double ratio = smallest / options.singular_region;
  const double damping2 =
      ratio >= 1 ? 0.0 : options.damping * options.damping * (1.0 - ratio * ratio);
  Eigen::Matrix<double, 6, 1> gains;
  for (int k = 0; k < 6; ++k) {
    const double denominator = sigma(k) * sigma(k) + damping2;
    gains(k) = denominator > 0 ? sigma(k) / denominator : 0.0;
  }
  const Eigen::Matrix<double, 6, 1> solution =
      svd.matrixV() * gains.asDiagonal() * (svd.matrixU().transpose() * twist);

  double fastest = 0;
  for (int i = 0; i < 6; ++i) fastest = std::max(fastest, std::abs(solution(i)));
  const double scale =
      fastest > options.max_joint_speed_rad_s ? options.max_joint_speed_rad_s / fastest : 1.0;
  for (int i = 0; i < 6; ++i) qd[i] = solution(i) * scale;
  return qd;
}

}  // namespace recon::teach
