#pragma once

#include <memory>
#include <string>

#include "engine/store/manifest.h"
#include "engine/worlds/world.h"

namespace recon::cli {

/// Builds the simulated world a session was recorded in, wired to the headless renderer when it
/// observes camera images. `placement` overrides the session's ("none" for rollouts, where the
/// beacons are removed). UserError for sessions that have no simulated world (imported ones).
std::unique_ptr<worlds::World> MakeSessionWorld(const store::SessionManifest& manifest,
                                                const std::string& placement);

}  // namespace recon::cli
