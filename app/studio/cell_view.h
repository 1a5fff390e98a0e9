#pragma once

#include <vector>

#include "engine/store/manifest.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/tabletop.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// Fills the snapshot's live view of the tabletop cell: the top camera at width x height, the
/// objects a beacon can be assigned to (where the camera sees them) and each beacon of the
/// session with its latest `reading` drawn where it projects.
void ShowTabletopView(worlds::Tabletop& world, worlds::SceneRenderer& renderer, int width,
                      int height, const store::SessionManifest& manifest,
                      const std::vector<float>& reading, ui::StudioSnapshot& snapshot);

}  // namespace recon::studio
