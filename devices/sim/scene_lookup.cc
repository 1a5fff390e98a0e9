#include "devices/sim/scene_lookup.h"

#include <mujoco/mujoco.h>

#include <vector>

#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace recon::sim {

namespace {

int FindNamed(const worlds::MujocoModel& scene, mjtObj type, int count, const char* kind,
              const std::string& name, const std::string& who) {
  const int id = mj_name2id(scene.model(), type, name.c_str());
  if (id >= 0) return id;
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) {
    const char* n = mj_id2name(scene.model(), type, i);
    if (n != nullptr && *n != '\0') names.emplace_back(n);
  }
  throw UserError(who + ": the scene has no " + kind + " '" + name + "' (its " + kind +
                  "s: " + (names.empty() ? std::string("none") : JoinNames(names)) + ")");
}

}  // namespace

int FindSite(const worlds::MujocoModel& scene, const std::string& name, const std::string& who) {
  return FindNamed(scene, mjOBJ_SITE, scene.model()->nsite, "site", name, who);
}

int FindCamera(const worlds::MujocoModel& scene, const std::string& name, const std::string& who) {
  return FindNamed(scene, mjOBJ_CAMERA, scene.model()->ncam, "camera", name, who);
}

}  // namespace recon::sim
