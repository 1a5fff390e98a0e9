#pragma once

#include <memory>
#include <optional>
#include <string>

#include "engine/store/manifest.h"
#include "engine/teach/session_setup.h"
#include "engine/worlds/world.h"

namespace recon::cli {

/// Builds the simulated world a session was recorded in, wired to the headless renderer when it
/// observes camera images. `placement` overrides the session's ("none" for rollouts, where the
/// beacons are removed). UserError for sessions that have no simulated world (imported ones).
std::unique_ptr<worlds::World> MakeSessionWorld(const store::SessionManifest& manifest,
                                                const std::string& placement);
/// The simulated world of the session's task whatever cell taught it, without MakeSessionWorld's
/// check: where the test plan's scenes put the objects, which a real cell's trials set up by
/// hand (World::ObjectLayout). Not a stand-in for a real cell's dynamics or camera.
std::unique_ptr<worlds::World> MakeSimulatedTaskWorld(const store::SessionManifest& manifest,
                                                      const std::string& placement);

/// The options that describe a new session's cell (`recon record`, `recon session repair`).
/// Empty strings and absent numbers take the world's defaults.
struct NewSessionOptions {
  std::string world;
  std::string placement;
  std::string layout;
  std::optional<double> beacon_noise;
  std::optional<double> demo_noise;
  int image_size = 64;
  uint64_t seed = 1;
};

/// The setup those options give; UserError for a missing world or an unknown layout.
teach::SessionSetup NewSessionSetup(const NewSessionOptions& options, const std::string& folder);

/// The fields of a manifest that choose a setup's world (what MakeSessionWorld and a real
/// cell's MakeWorld read), before the session exists.
store::SessionManifest WorldManifest(const teach::SessionSetup& setup);

/// The simulated world a setup records in.
std::unique_ptr<worlds::World> MakeSetupWorld(const teach::SessionSetup& setup);

}  // namespace recon::cli
