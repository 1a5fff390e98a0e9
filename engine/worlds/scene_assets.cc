#include "engine/worlds/scene_assets.h"

#include <map>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/embedded_assets.h"

namespace recon::worlds {

namespace {

constexpr char kMjcfFolder[] = "mjcf/";

// Embedded MJCF files by bare file name: scenes include each other by that name.
const std::map<std::string, std::string>& MjcfFiles() {
  static const std::map<std::string, std::string> files = [] {
    std::map<std::string, std::string> result;
    const std::string folder = kMjcfFolder;
    for (const EmbeddedAsset& asset : EmbeddedAssets()) {
      const std::string path = asset.path;
      if (path.rfind(folder, 0) == 0) result[path.substr(folder.size())] = asset.contents;
    }
    return result;
  }();
  return files;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::vector<std::string> SceneNames() {
  std::vector<std::string> names;
  for (const auto& [file, text] : MjcfFiles()) {
    // Scenes are whole models (<mujoco>); parts such as the arm are <mujocoinclude>.
    if (text.find("<mujocoinclude") == std::string::npos)
      names.push_back(file.substr(0, file.size() - 4));
  }
  return names;
}

const std::string& SceneText(const std::string& file_name) {
  const auto it = MjcfFiles().find(file_name);
  if (it == MjcfFiles().end()) throw UserError("no embedded MJCF file named " + file_name);
  return it->second;
}

MujocoModel LoadScene(const std::string& scene) {
  if (EndsWith(scene, ".xml")) return MujocoModel::FromFile(scene);
  const std::vector<std::string> names = SceneNames();
  bool known = false;
  for (const std::string& name : names) known = known || name == scene;
  if (!known) {
    throw UserError("unknown scene '" + scene + "' (known scenes: " + JoinNames(names) +
                    "; or give an MJCF file ending in .xml)");
  }
  std::vector<std::pair<std::string, std::string>> files(MjcfFiles().begin(), MjcfFiles().end());
  return MujocoModel::FromFiles(files, scene + ".xml", "scene " + scene);
}

}  // namespace recon::worlds
