// What the tabletop's gripper does, for a teacher's readout (the studio's Record screen): the
// state of its grip on the toast, the heights at which a grasp holds, and what lies under it.

#include <mujoco/mujoco.h>

#include "engine/worlds/tabletop.h"

namespace recon::worlds {

ToastGrip Tabletop::GripOnToast() const {
  if (arm_->HeldObject() == toast_body_) return ToastGrip::kHolding;
  if (!arm_->GripperClosed()) return ToastGrip::kOpen;
  return arm_->FingersClosing() ? ToastGrip::kClosing : ToastGrip::kClosedOnNothing;
}

Eigen::Vector3d Tabletop::SurfaceBelowGrip() const {
  const Eigen::Vector3d grip = arm_->GripPosition();
  // Straight down from well above, past the arm (its geoms are group 1, left out): the spot
  // stays on the toast's top while the finger tips go down beside it, as a person sees it. A
  // held toast is left out too: the spot shows where it will land.
  const mjtNum start[3] = {grip.x(), grip.y(), grip.z() + 0.5};
  const mjtNum down[3] = {0, 0, -1};
  // Groups 0 (the objects, the table) and 2 (the tags), not 1 (the arm) nor 3 (the plate's
  // invisible collision box).
  const mjtByte groups[mjNGROUP] = {1, 0, 1, 0, 0, 0};
  int geom = -1;
  const int exclude = arm_->HeldObject() == toast_body_ ? toast_body_ : -1;
  const mjtNum distance =
      mj_ray(scene_.model(), scene_.data(), start, down, groups, 1, exclude, &geom);
  if (geom < 0 || distance < 0) return {grip.x(), grip.y(), 0.0};
  return {grip.x(), grip.y(), start[2] - distance};
}

std::pair<double, double> Tabletop::GraspHeights() const {
  const double floor = safety_limits().tool_floor_m;
  return {floor, arm_->HighestGraspHeight("toast").value_or(floor)};
}

}  // namespace recon::worlds
