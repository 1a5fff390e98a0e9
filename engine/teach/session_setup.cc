#include "engine/teach/session_setup.h"

#include "engine/core/error.h"
#include "engine/store/episode_file.h"
#include "engine/worlds/world_factory.h"

namespace recon::teach {

std::string DefaultTeachingPlacement(const std::string& world) {
  if (world == "dynamic2d" || world == "dynamic2d-state") return "exact";
  if (world == "tabletop" || world == "tabletop-state") return "plate";
  worlds::WorldPlacements(world);  // UserError for an unknown world
  return "position";
}

store::SessionManifest NewSessionManifest(const SessionSetup& setup, const worlds::World& world) {
  store::SessionManifest m;
  m.created_at = store::NowIso8601();
  m.created_by = "recon 0.1.0";
  m.world = setup.world_name;
  m.cell = "simulated";
  m.placement = setup.placement;
  m.layout = setup.layout;
  m.beacon_noise_sigma = setup.beacon_noise_sigma;
  m.demo_noise_sigma = setup.demo_noise_sigma;
  m.image_size = worlds::WorldNeedsRenderer(setup.world_name) ? setup.image_size : 0;
  m.step_seconds = world.StepSeconds();
  m.beacons = worlds::BeaconLayout(setup.world_name, setup.placement);
  m.spec = world.Spec();
  // Camera pixels are whole numbers 0-255: stored as robomimic's uint8 HWC images. The 2-D
  // worlds' drawings have fractional colours and keep float32.
  m.y_encoding = m.image_size > 0 ? "uint8" : "float32";
  m.seed = setup.seed;
  if (m.image_size > 0 || setup.world_name == "bintransfer") {
    m.devices = {{"arm", "simulated", "UR5 in MuJoCo, 10 Hz joint-velocity control"},
                 {"beacons", "simulated", "DWM1001 lec lines through the serial parser"},
                 {"teleop", "scripted", "the world's scripted expert"}};
    if (m.image_size > 0) {
      m.devices.insert(m.devices.begin(),
                       {"camera", "simulated",
                        "top camera, " + std::to_string(m.image_size) + "x" +
                            std::to_string(m.image_size) + " RGB (MuJoCo, EGL)"});
    }
  } else {
    m.devices = {{"teleop", "scripted", "the world's scripted expert (abstract 2-D world)"}};
  }
  return m;
}

void CheckSessionMatches(const store::SessionManifest& manifest, const SessionSetup& setup) {
  const auto mismatch = [&](const std::string& field, const std::string& session_value,
                            const std::string& asked) {
    throw UserError("the session records " + field + " '" + session_value + "' but '" + asked +
                    "' was asked for; a session keeps one " + field +
                    " (start a new session with another --session folder)");
  };
  if (manifest.world != setup.world_name) mismatch("world", manifest.world, setup.world_name);
  if (manifest.placement != setup.placement) {
    mismatch("placement", manifest.placement, setup.placement);
  }
  if (manifest.layout != setup.layout) mismatch("layout", manifest.layout, setup.layout);
  if (manifest.image_size > 0 && manifest.image_size != setup.image_size) {
    mismatch("image size", std::to_string(manifest.image_size), std::to_string(setup.image_size));
  }
}

}  // namespace recon::teach
