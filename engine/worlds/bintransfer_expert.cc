// BinTransfer's scripted expert: the joint-space waypoints it plans for a scene (above the
// target, the grasp, above the right bin, the release), the phase it is in, and its action.

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/core/error.h"
#include "engine/worlds/bintransfer.h"

namespace recon::worlds {

std::optional<Ur5Joints> BinTransfer::SolveWaypoint(const Eigen::Vector3d& grip,
                                                    const Ur5Joints& seed) const {
  // Turning wrist 3 turns the fingers about the vertical by the same angle the other way (the
  // tool points down), so a first solution's wrist-3 offset from home tells the yaw that needs no
  // wrist-3 rotation at all; the gripper is symmetric, so any yaw grasps. The first guess follows
  // the bearing of the grip point, as the shoulder pan will.
  const double first_yaw = home_yaw_rad_ + std::atan2(grip.y(), grip.x()) - home_bearing_rad_;
  const auto first = arm_->SolveGraspIk(grip, first_yaw, seed);
  if (!first) return std::nullopt;
  const double yaw = first_yaw + ((*first)[5] - Ur5Arm::kHome[5]);
  return arm_->SolveGraspIk(grip, yaw, *first);
}

void BinTransfer::PlanExpert() {
  const Eigen::Vector3d target = ObjectPosition(target_);
  above_target_ = Eigen::Vector3d(target.x(), target.y(), kCarryHeight_m);
  const auto above = SolveWaypoint(above_target_, Ur5Arm::kHome);
  const auto grasp = above ? SolveWaypoint(target, *above) : std::nullopt;
  if (!grasp) {
    char message[256];
    std::snprintf(message, sizeof(message),
                  "bintransfer: the UR5 cannot reach the target object %s at (%.3f, %.3f, %.3f) m "
                  "with its tool pointing down; the layout is unreachable",
                  ObjectNames()[target_], target.x(), target.y(), target.z());
    throw UserError(message);
  }
  q_above_target_ = *above;
  q_grasp_ = *grasp;
}

void BinTransfer::UpdatePhase() {
  const Eigen::Vector3d grip = arm_->GripPosition();
  if (released_) {
    phase_ = Phase::kDone;
    return;
  }
  switch (phase_) {
    case Phase::kApproach:
      if (TargetHeld()) {
        phase_ = Phase::kLift;
      } else if ((grip - above_target_).norm() < kWaypointTolerance_m) {
        phase_ = Phase::kDescend;
      }
      break;
    case Phase::kDescend:
      if (TargetHeld()) phase_ = Phase::kLift;
      break;
    case Phase::kLift:
      if ((grip - above_target_).norm() < kWaypointTolerance_m) phase_ = Phase::kTransfer;
      break;
    case Phase::kTransfer:
      if ((grip - above_bin_).norm() < kWaypointTolerance_m) phase_ = Phase::kLower;
      break;
    case Phase::kLower:
    case Phase::kDone:
      break;
  }
}

std::vector<float> BinTransfer::ExpertAction() const {
  std::vector<float> u(Ur5Arm::kJoints, 0.0f);
  const Ur5Joints* goal = nullptr;
  switch (phase_) {
    case Phase::kApproach:
    case Phase::kLift:
      goal = &q_above_target_;
      break;
    case Phase::kDescend:
      goal = &q_grasp_;
      break;
    case Phase::kTransfer:
      goal = &q_above_bin_;
      break;
    case Phase::kLower:
      goal = &q_release_;
      break;
    case Phase::kDone:
      return u;
  }
  const Ur5Joints q = arm_->JointPositions();
  Ur5Joints qd;
  double fastest = 0.0;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) {
    qd[i] = kExpertGain_per_s * ((*goal)[i] - q[i]);
    fastest = std::max(fastest, std::abs(qd[i]));
  }
  // Scale all joints together so the arm still moves straight toward the goal in joint space.
  const double scale = fastest > kExpertMaxSpeed_rad_s ? kExpertMaxSpeed_rad_s / fastest : 1.0;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) u[i] = static_cast<float>(scale * qd[i]);
  return u;
}

}  // namespace recon::worlds
