#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ui/studio/studio_snapshot.h"
#include "ui/widgets/image_texture.h"

namespace recon::ui {

/// The live camera image scaled to `width` pixels, with the beacons' readings drawn over it
/// (a ring and a label where each projects) and, when `objects` is not empty, the objects as
/// click targets. Returns the object the teacher clicked this frame, if any.
std::optional<std::string> CameraView(const char* id, const ImageTexture& texture, float width,
                                      const std::vector<BeaconView>& beacons,
                                      const std::vector<ObjectView>& objects);

}  // namespace recon::ui
