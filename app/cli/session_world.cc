#include "app/cli/session_world.h"

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
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
  worlds::CellResources cell;
  if (worlds::WorldNeedsRenderer(manifest.world)) {
    cell.renderer_factory = render::MujocoRendererFactory();
    cell.image_size = manifest.image_size;
  }
  if (!manifest.layout.empty()) cell.layout = manifest.layout;
  return worlds::MakeWorld(manifest.world, placement, manifest.beacon_noise_sigma, false, cell);
}

}  // namespace recon::cli
