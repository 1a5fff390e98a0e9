// The tabletop's scripted teacher (Tabletop::ExpertAction): above the toast, down onto it, close,
// lift, over the plate, down, open, back up; a person at the joystick's pace.

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/worlds/tabletop.h"
#include "engine/worlds/tabletop_waypoints.h"

namespace recon::worlds {

using namespace tabletop_waypoints;  // NOLINT(build/namespaces): its waypoints, throughout

std::vector<float> Tabletop::ExpertAction() const {
  const Eigen::Vector3d grip = arm_->GripPosition();
  const Eigen::Vector3d toast = ToastPosition();
  const Eigen::Vector3d plate = PlatePosition();
  const bool holding = arm_->HeldObject() == toast_body_;
  const bool delivered =
      !holding && PlanarDistance(toast, plate) < kPlateRadius_m && toast.z() < kApproachHeight_m;
  bool close = holding;
  Eigen::Vector3d target;
  if (holding && arm_->FingersClosing()) {
    // A person waits for the fingers to close on the slice before lifting it.
    target = grip;
  } else if (holding) {
    if (PlanarDistance(grip, plate) > kReleaseTolerance_m) {
      // Lift straight up first: a joint-space move from the grasp would sweep the toast along
      // the table.
      target = grip.z() < kLiftFirstBelow_m ? Eigen::Vector3d(grip.x(), grip.y(), kCarryHeight_m)
                                            : plate + Eigen::Vector3d(0, 0, kCarryHeight_m);
    } else {
      target = plate + Eigen::Vector3d(0, 0, kReleaseHeight_m);
      // Low over the plate: open and let the toast drop onto it.
      if ((grip - target).norm() < kReleaseTolerance_m) close = false;
    }
  } else if (delivered) {
    target = plate + Eigen::Vector3d(0, 0, kRetreatHeight_m);
  } else if (PlanarDistance(grip, toast) > kAlignTolerance_m &&
             !(PlanarDistance(grip, toast) < kDescentTolerance_m &&
               grip.z() < toast.z() + kApproachHeight_m - 0.02)) {
    // Above the toast first; once descending, a joint-space move may drift a little sideways,
    // which must not send the arm back up (hysteresis).
    target = toast + Eigen::Vector3d(0, 0, kApproachHeight_m);
  } else {
    target = toast - Eigen::Vector3d(0, 0, kDescentBelowCentre_m);
    // Close once inside the window, still pushing down: the fingers take 0.6 s to reach the
    // slice (Ur5Arm), and a learner that closes a little early is still caught as it comes
    // down. A close that caught nothing opens again for another try.
    const bool missed = arm_->GripperClosed() && !arm_->FingersClosing();
    close = !missed && PlanarDistance(grip, toast) < kGraspTolerance_m &&
            grip.z() - toast.z() < kCloseHeight_m;
  }
  const Ur5Joints q = arm_->JointPositions();
  const auto goal = arm_->SolveGraspIk(target, 0.0, q);
  std::vector<float> u(Ur5Arm::kJoints + 1);
  // Reset checked that the layout is reachable; a target out of reach here comes from a state a
  // policy drove the arm into (e.g. toast flung up), where the teacher would hold still.
  if (!goal) return u;
  // Proportional in joint space, scaled as a whole (not clamped per joint) so the arm keeps to
  // the straight joint-space path: clamping joints separately bends the descent sideways.
  std::array<double, Ur5Arm::kJoints> v{};
  double fastest = 0.0;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) {
    v[i] = kExpertGain_per_s * ((*goal)[i] - q[i]);
    fastest = std::max(fastest, std::abs(v[i]));
  }
  const double scale = fastest > kExpertMaxSpeed_rad_s ? kExpertMaxSpeed_rad_s / fastest : 1.0;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) u[i] = static_cast<float>(v[i] * scale);
  u[Ur5Arm::kJoints] = close ? 1.0f : 0.0f;
  return u;
}

}  // namespace recon::worlds
