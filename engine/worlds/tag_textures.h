#pragma once

#include "engine/worlds/mujoco_model.h"

namespace recon::worlds {

/// Paints every texture named "tag36h11_<id>" in the scene with that AprilTag (tag_bitmap.h), so
/// the simulated camera sees real tags. Call after compiling and before a renderer uploads the
/// textures. Rows are copied as TagTextureRgb gives them (row 0 first): on the plane geoms the
/// scenes use, that shows the tag as printed, whereas reversing the rows shows its mirror image,
/// which AprilTag does not decode (tests/render/cell_render_test.cc detects every tag of a
/// rendered frame). UserError for a texture that is not square or an id out of range.
void PaintTagTextures(MujocoModel& scene);

}  // namespace recon::worlds
