#pragma once

#include <cstdint>
#include <string>

#include "engine/store/manifest.h"
#include "engine/worlds/world.h"

namespace recon::teach {

/// The beacon placement a teacher uses in a world unless told otherwise: the paper's RECON
/// condition (dynamic2d "exact", static2d and bintransfer "position", tabletop "plate").
std::string DefaultTeachingPlacement(const std::string& world);

/// What a new session records about its cell: the world and placement, the devices (simulated
/// here), the beacons and the shapes. `world` is the instance that will record.
struct SessionSetup {
  std::string world_name;
  std::string placement;
  std::string layout;  ///< the world's scene layout (empty for worlds without layouts)
  double beacon_noise_sigma = 0;
  double demo_noise_sigma = 0;  ///< DART noise while demonstrating (worlds::DemoNoise)
  int image_size = 0;           ///< 0 for worlds without a camera
  uint64_t seed = 1;
};
store::SessionManifest NewSessionManifest(const SessionSetup& setup, const worlds::World& world);

/// UserError when `setup` does not match an existing session's manifest (another world,
/// placement, layout or image size), naming the field and both values.
void CheckSessionMatches(const store::SessionManifest& manifest, const SessionSetup& setup);

}  // namespace recon::teach
