#pragma once

#include <string>

#include "engine/worlds/mujoco_model.h"

namespace recon::sim {

/// The id of the site `name` in `scene`. UserError naming `who` (e.g. "simulated beacon 'plate'")
/// and the site, and listing the scene's sites, when there is none.
int FindSite(const worlds::MujocoModel& scene, const std::string& name, const std::string& who);

/// The id of the camera `name` in `scene`; UserError as FindSite, listing the cameras.
int FindCamera(const worlds::MujocoModel& scene, const std::string& name, const std::string& who);

}  // namespace recon::sim
