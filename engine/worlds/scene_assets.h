#pragma once

#include <string>
#include <vector>

#include "engine/worlds/mujoco_model.h"

namespace recon::worlds {

/// Names of the MuJoCo scenes compiled into the program (assets/mjcf/<name>.xml), e.g.
/// "bintransfer", "tabletop".
std::vector<std::string> SceneNames();

/// The text of an embedded MJCF file, e.g. SceneText("ur5.xml"). UserError if there is none.
const std::string& SceneText(const std::string& file_name);

/// Compiles a scene: an embedded scene by name, or an MJCF file on disk when `scene` ends in
/// ".xml". UserError naming the scene (or file) and MuJoCo's reason when it is unknown, missing
/// or invalid.
MujocoModel LoadScene(const std::string& scene);

}  // namespace recon::worlds
