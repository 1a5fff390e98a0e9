#include "ui/screens/grip_readout.h"

namespace recon::ui {

namespace {

// The grasp hints show once the grip point is this close to the object in the plane: away from
// it, the arrows are what matters, not the jaw or the height.
constexpr float kNearObject_m = 0.08f;

/// What to do next to grasp, from where the object lies across the open fingers and how high
/// they are: the jaw's axis first (a close off it catches nothing however low), then the height.
std::string GraspHint(const StudioSnapshot& s) {
  const GripView& g = s.grip;
  const bool band = g.grasp_max_m > g.grasp_min_m;
  const bool near = !g.alignment_known || g.object_distance_m < kNearObject_m;
  if (g.state == GripState::kClosedOnNothing) {
    if (g.alignment_known && g.off_axis_m > g.off_axis_window_m && near) {
      return Format("It closed %.1f cm off the jaw's axis: open (Space) and line up",
                    100 * (g.off_axis_m - g.off_axis_window_m));
    }
    return "";
  }
  if (g.state != GripState::kOpen || !band || !near) return "";
  if (g.alignment_known) {
    if (g.off_axis_m > g.off_axis_window_m) {
      return Format("%.1f cm off the jaw's axis (cyan): move across it, or turn the wrist",
                    100 * (g.off_axis_m - g.off_axis_window_m));
    }
    if (g.beyond_pads_m > g.beyond_pads_window_m) {
      return Format("%.1f cm beyond the finger pads: move along the cyan line",
                    100 * (g.beyond_pads_m - g.beyond_pads_window_m));
    }
  }
  const float above = s.grip_m[2] - g.grasp_max_m;
  if (above > 0 && above < 0.05f) return Format("lower %.1f cm more before closing", 100 * above);
  if (above <= 0) return "Low enough: close the gripper";
  return "";
}

}  // namespace

GripReadout ReadGrip(const StudioSnapshot& s) {
  GripReadout r;
  const std::string object = s.grip.object.empty() ? "the object" : "the " + s.grip.object;
  switch (s.grip.state) {
    case GripState::kHolding:
      r = {Status::kOk, "Holding " + object};
      break;
    case GripState::kClosedOnNothing:
      r = {Status::kError, "Closed on nothing: open (Space), line up and try again"};
      break;
    case GripState::kClosing:
      r = {Status::kBusy, "Closing..."};
      break;
    case GripState::kOpen:
      r = {Status::kOff, "Gripper open"};
      break;
    case GripState::kUnknown:
      r = {Status::kOff, s.gripper_closed ? "Gripper closed" : "Gripper open"};
      break;
  }
  const float height = s.grip_m[2];
  const bool band = s.grip.grasp_max_m > s.grip.grasp_min_m;
  // Holding, the heights at which a grasp would hold say nothing: they follow the lifted object.
  if (s.grip.state == GripState::kHolding) {
    r.height = Format("Height %.1f cm, carrying %s", 100 * height, object.c_str());
  } else if (band) {
    r.height = Format("Height %.1f cm; it grasps %s at %.1f-%.1f cm", 100 * height, object.c_str(),
                      100 * s.grip.grasp_min_m, 100 * s.grip.grasp_max_m);
  } else {
    r.height = Format("Height %.1f cm", 100 * height);
  }
  r.hint = GraspHint(s);
  return r;
}

}  // namespace recon::ui
