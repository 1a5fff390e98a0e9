#include "ui/screens/grip_readout.h"

#include <cmath>

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

/// The wrist's line. Home turns it one way (positive), End and the right stick pushed right the
/// other (gamepad_mapping.cc); at a limit the teleop holds it there however long a key is held
/// (cartesian_teleop.cc), and the line says what turns it back.
void WristLine(const StudioSnapshot& s, GripReadout& r) {
  const GripView& g = s.grip;
  if (s.teleop == TeleopMode::kScripted || g.wrist_limit_deg <= 0) return;
  const bool gamepad = s.teleop == TeleopMode::kGamepad;
  // Short lines: the readout is as narrow as the smallest 3-D view.
  if (std::abs(g.wrist_turn_deg) >= g.wrist_limit_deg - 0.5f) {
    const bool positive = g.wrist_turn_deg > 0;
    const char* back = gamepad
                           ? (positive ? "push the right stick right" : "push the right stick left")
                           : (positive ? "turn back with End" : "turn back with Home");
    r.wrist_status = Status::kWarning;
    r.wrist = Format("Wrist at its %.0f\xc2\xb0 limit: %s", g.wrist_limit_deg, back);
    return;
  }
  // Rounded, so that a turn of -0.2 degrees does not read "-0".
  const float turn = std::round(g.wrist_turn_deg);
  r.wrist_status = Status::kOff;
  r.wrist =
      Format("Wrist turned %.0f\xc2\xb0 (%s, up to %.0f\xc2\xb0 either way)",
             turn == 0.0f ? 0.0f : turn, gamepad ? "right stick" : "Home / End", g.wrist_limit_deg);
}

}  // namespace

GripReadout ReadGrip(const StudioSnapshot& s) {
  GripReadout r;
  const std::string object = s.grip.object.empty() ? "the object" : "the " + s.grip.object;
  switch (s.grip.state) {
    case GripState::kHolding:
      r.status = Status::kOk;
      r.state = "Holding " + object;
      break;
    case GripState::kClosedOnNothing:
      r.status = Status::kError;
      r.state = "Closed on nothing: open (Space), line up and try again";
      break;
    case GripState::kClosing:
      r.status = Status::kBusy;
      r.state = "Closing...";
      break;
    case GripState::kOpen:
      r.status = Status::kOff;
      r.state = "Gripper open";
      break;
    case GripState::kUnknown:
      r.status = Status::kOff;
      r.state = s.gripper_closed ? "Gripper closed" : "Gripper open";
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
  WristLine(s, r);
  return r;
}

}  // namespace recon::ui
