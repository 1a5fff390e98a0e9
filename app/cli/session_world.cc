#include "app/cli/session_world.h"

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/world_factory.h"

namespace recon::cli {

std::unique_ptr<worlds::World> MakeSessionWorld(const store::SessionManifest& manifest,
                                                const std::string& placement) {
  if (manifest.cell != "simulated") {
    throw UserError("this session was recorded in a " + manifest.cell + " cell (world '" +
                    manifest.world +
                    "'), which RECON Studio cannot simulate: train on it, but roll out on the "
                    "cell it came from");
  }
  return MakeSimulatedTaskWorld(manifest, placement);
}

std::unique_ptr<worlds::World> MakeSimulatedTaskWorld(const store::SessionManifest& manifest,
                                                      const std::string& placement) {
  worlds::CellResources cell;
  if (worlds::WorldNeedsRenderer(manifest.world)) {
    cell.renderer_factory = render::MujocoRendererFactory();
    cell.image_size = manifest.image_size;
  }
  if (!manifest.layout.empty()) cell.layout = manifest.layout;
  return worlds::MakeWorld(manifest.world, placement, manifest.beacon_noise_sigma, false, cell);
}

teach::SessionSetup NewSessionSetup(const NewSessionOptions& options, const std::string& folder) {
  if (options.world.empty()) {
    throw UserError(folder + " is not a session yet: give --world (" +
                    JoinNames(worlds::WorldNames()) + ") to start one");
  }
  teach::SessionSetup setup;
  setup.world_name = options.world;
  setup.placement = options.placement.empty() ? teach::DefaultTeachingPlacement(options.world)
                                              : options.placement;
  setup.image_size = options.image_size;
  setup.seed = options.seed;
  setup.layout = worlds::ChooseLayout(options.world, options.layout, "--layout");
  setup.beacon_noise_sigma =
      options.beacon_noise.value_or(worlds::DefaultBeaconNoise(options.world));
  setup.demo_noise_sigma = options.demo_noise.value_or(worlds::DefaultDemoNoise(options.world));
  return setup;
}

store::SessionManifest WorldManifest(const teach::SessionSetup& setup) {
  store::SessionManifest probe;
  probe.world = setup.world_name;
  probe.placement = setup.placement;
  probe.image_size = setup.image_size;
  probe.layout = setup.layout;
  probe.beacon_noise_sigma = setup.beacon_noise_sigma;
  return probe;
}

std::unique_ptr<worlds::World> MakeSetupWorld(const teach::SessionSetup& setup) {
  return MakeSessionWorld(WorldManifest(setup), setup.placement);
}

}  // namespace recon::cli
