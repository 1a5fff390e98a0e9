// Tabletop's objects moved by a tool (the distractor probe, engine/probe): one object to a new
// place on the table, everything else held, and the camera image drawn again.

#include <mujoco/mujoco.h>

#include <string>

#include "engine/core/error.h"
#include "engine/worlds/tabletop.h"

namespace recon::worlds {

std::optional<ObjectArea> Tabletop::PlaceableArea() const {
  ObjectArea area;
  area.x_min = kBowlMinX;
  area.x_max = kBowlMaxX;
  area.y_min = -kBowlMaxAbsY;
  area.y_max = kBowlMaxAbsY;
  area.radius_m = {{"plate", kPlateRadius_m}, {"bowl", kBowlRadius_m}, {"toast", kToastRadius_m}};
  return area;
}

void Tabletop::PlaceObject(const std::string& object, const std::array<double, 2>& xy) {
  mjData* d = scene_.data();
  if (object == "plate" || object == "bowl") {
    const int body = object == "plate" ? plate_body_ : bowl_body_;
    const int mocap = scene_.model()->body_mocapid[body];
    d->mocap_pos[3 * mocap] = xy[0];  // the plate carries its beacon along
    d->mocap_pos[3 * mocap + 1] = xy[1];
  } else if (object == "toast") {
    d->qpos[toast_qpos_] = xy[0];
    d->qpos[toast_qpos_ + 1] = xy[1];
  } else {
    throw UserError("the tabletop has no object \"" + object + "\" (valid: bowl, plate, toast)");
  }
  mj_forward(scene_.model(), d);
  plate_side_ = PlatePosition().y() >= 0 ? 1 : -1;
  closest_approach_m_ = (arm_->GripPosition() - ToastPosition()).norm();
  Render();
}

bool Tabletop::TaskFeasible() const {
  try {
    CheckReachable();
    return true;
  } catch (const UserError&) {
    return false;  // a grasp or release place out of the arm's reach
  }
}

}  // namespace recon::worlds
