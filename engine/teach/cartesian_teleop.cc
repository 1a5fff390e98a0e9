#include "engine/teach/cartesian_teleop.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/safety/ur5_kinematics.h"
#include "engine/teach/resolved_rate.h"

namespace recon::teach {

TeleopArm TeleopArmOf(const safety::SafetyLimits& limits) {
  TeleopArm arm;
  arm.base_in_table = limits.base_in_table;
  arm.tool_offset_m = limits.tool_offset_m;
  return arm;
}

double WristTurn(const std::array<double, 6>& q_rad, const TeleopArm& arm) {
  // The flange's x axis on the table, now and at home: the tool points down in both, so the
  // angle between them is the turn about the vertical.
  const auto heading = [&](const std::array<double, 6>& q) {
    const Eigen::Vector3d x = arm.base_in_table.linear() * safety::Ur5FlangePose(q).linear().col(0);
    return std::atan2(x.y(), x.x());
  };
  std::array<double, 6> home;
  for (int i = 0; i < 6; ++i) home[i] = worlds::Ur5Arm::kHome[i];
  return std::remainder(heading(q_rad) - heading(home), 2 * M_PI);
}

std::vector<float> CartesianTeleopAction(const std::array<double, 6>& q_rad,
                                         const TeleopCommand& command, const TeleopArm& arm,
                                         double period_s, const CartesianTeleopLimits& limits) {
  std::vector<float> u(7, 0.0f);
  u[6] = command.close_gripper ? 1.0f : 0.0f;
  Eigen::Vector3d velocity = command.velocity_m_s;
  double turn = std::isfinite(command.wrist_turn_rad_s) ? command.wrist_turn_rad_s : 0.0;
  if (turn != 0.0) {
    // No further than a period takes the wrist to its limit.
    const double now = WristTurn(q_rad, arm);
    turn = std::clamp(turn, std::min(0.0, (-kMaxWristTurn_rad - now) / period_s),
                      std::max(0.0, (kMaxWristTurn_rad - now) / period_s));
  }
  if (!velocity.allFinite() || (velocity.isZero(0.0) && turn == 0.0)) return u;
  // The height limits: no further than a period takes the tool point to them.
  const double z = (arm.base_in_table * safety::Ur5ToolPoint(q_rad, arm.tool_offset_m)).z();
  velocity.z() = std::clamp(velocity.z(), std::min(0.0, (limits.min_grip_height_m - z) / period_s),
                            std::max(0.0, (limits.max_grip_height_m - z) / period_s));
  CartesianVelocityOptions options;
  options.tool_offset_m = arm.tool_offset_m;
  options.max_joint_speed_rad_s = limits.max_joint_speed_rad_s;
  const std::array<double, 6> qd = CartesianJointVelocities(
      q_rad, velocity, Eigen::Vector3d(0, 0, turn), arm.base_in_table, options);
  for (int i = 0; i < 6; ++i) u[i] = static_cast<float>(qd[i]);
  return u;
}

std::vector<float> CartesianTeleopAction(worlds::Tabletop& world, const TeleopCommand& command,
                                         const CartesianTeleopLimits& limits) {
  return CartesianTeleopAction(world.arm().JointPositions(), command,
                               TeleopArmOf(world.safety_limits()),
                               worlds::Tabletop::kControlPeriod_s, limits);
}

Teacher CartesianTeleopTeacher(std::function<std::array<double, 6>()> joints,
                               const TeleopCommand* command, const TeleopArm& arm, double period_s,
                               const CartesianTeleopLimits& limits) {
  return [joints = std::move(joints), command, arm, period_s, limits](const worlds::World&) {
    return TeacherAction{CartesianTeleopAction(joints(), *command, arm, period_s, limits),
                         command->finish};
  };
}

Teacher CartesianTeleopTeacher(const safety::GuardedArm& arm, const TeleopCommand* command,
                               double period_s, const CartesianTeleopLimits& limits) {
  return CartesianTeleopTeacher([&arm] { return arm.State().position_rad; }, command,
                                TeleopArmOf(arm.envelope().limits()), period_s, limits);
}

Teacher CartesianTeleopTeacher(worlds::Tabletop& world, const TeleopCommand* command,
                               const CartesianTeleopLimits& limits) {
  return CartesianTeleopTeacher(world.guarded_arm(), command, worlds::Tabletop::kControlPeriod_s,
                                limits);
}

}  // namespace recon::teach
