#include "engine/teach/cartesian_teleop.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <mujoco/mujoco.h>

namespace recon::teach {

namespace {

/// The yaw of the fingers' closing axis about the vertical, as Ur5Arm::SolveGraspIk defines it
/// (its desired frame has the x axis at (cos yaw, sin yaw, 0)).
double CurrentToolYaw(worlds::Tabletop& world) {
  const mjModel* m = world.scene().model();
  const mjData* d = world.scene().data();
  const int site = mj_name2id(m, mjOBJ_SITE, "ur5_grip");
  if (site < 0) return 0.0;
  const mjtNum* r = d->site_xmat + 9 * site;  // row-major: the x axis is the first column
  return std::atan2(r[3], r[0]);
}

}  // namespace

std::vector<float> CartesianTeleopAction(worlds::Tabletop& world, const TeleopCommand& command,
                                         const CartesianTeleopLimits& limits) {
  worlds::Ur5Arm& arm = world.arm();
  std::vector<float> u(worlds::Ur5Arm::kJoints + 1, 0.0f);
  u[worlds::Ur5Arm::kJoints] = command.close_gripper ? 1.0f : 0.0f;
  if (!command.velocity_m_s.allFinite() || command.velocity_m_s.isZero()) return u;
  const double period = worlds::Tabletop::kControlPeriod_s;
  const Eigen::Vector3d grip = arm.GripPosition();
  Eigen::Vector3d target = grip + command.velocity_m_s * period;
  target.z() = std::clamp(target.z(), limits.min_grip_height_m, limits.max_grip_height_m);
  const worlds::Ur5Joints q = arm.JointPositions();
  // Keep the tool's current yaw: the teleop translates the grip point, and turning the wrist to
  // some fixed yaw would eat the joint-speed budget of the first steps.
  const auto goal = arm.SolveGraspIk(target, CurrentToolYaw(world), q);
  if (!goal) return u;  // out of reach: hold still rather than fling the arm
  // Reach the target in one control period, scaled as a whole (not clamped per joint) so the
  // grip point keeps to the commanded direction.
  std::array<double, worlds::Ur5Arm::kJoints> v{};
  double fastest = 0.0;
  for (int i = 0; i < worlds::Ur5Arm::kJoints; ++i) {
    v[i] = ((*goal)[i] - q[i]) / period;
    fastest = std::max(fastest, std::abs(v[i]));
  }
  const double scale =
      fastest > limits.max_joint_speed_rad_s ? limits.max_joint_speed_rad_s / fastest : 1.0;
  for (int i = 0; i < worlds::Ur5Arm::kJoints; ++i) u[i] = static_cast<float>(v[i] * scale);
  return u;
}

Teacher CartesianTeleopTeacher(worlds::Tabletop& world, const TeleopCommand* command,
                               const CartesianTeleopLimits& limits) {
  return [&world, command, limits](const worlds::World&) {
    return TeacherAction{CartesianTeleopAction(world, *command, limits), command->finish};
  };
}

}  // namespace recon::teach
