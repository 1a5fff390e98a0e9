#include "engine/worlds/tag_textures.h"

#include <mujoco/mujoco.h>

#include <cstring>
#include <string>

#include "engine/core/error.h"
#include "engine/worlds/tag_bitmap.h"

namespace recon::worlds {

void PaintTagTextures(MujocoModel& scene) {
  mjModel* m = scene.mutable_model();
  const std::string prefix = "tag36h11_";
  for (int t = 0; t < m->ntex; ++t) {
    const char* name = mj_id2name(m, mjOBJ_TEXTURE, t);
    if (name == nullptr || std::string(name).rfind(prefix, 0) != 0) continue;
    const std::string id_text = std::string(name).substr(prefix.size());
    int id = -1;
    try {
      id = std::stoi(id_text);
    } catch (const std::exception&) {
      throw UserError(std::string("texture '") + name + "' does not end in a tag id");
    }
    const int width = m->tex_width[t], height = m->tex_height[t];
    if (width != height) {
      throw UserError(std::string("tag texture '") + name + "' must be square, not " +
                      std::to_string(width) + " x " + std::to_string(height));
    }
    const std::vector<uint8_t> rgb = TagTextureRgb(id, width);
    mjtByte* texels = m->tex_rgb + m->tex_adr[t];
    std::memcpy(texels, rgb.data(), rgb.size());
  }
}

}  // namespace recon::worlds
