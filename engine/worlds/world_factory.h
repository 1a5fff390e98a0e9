#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/worlds/world.h"

namespace recon::worlds {

/// Names MakeWorld accepts: "dynamic2d" (image observations), "dynamic2d-state" (the 14-vector
/// state instead of the image) and "static2d".
const std::vector<std::string>& WorldNames();

/// Valid beacon placements of a world (throws UserError naming the valid worlds for an unknown
/// name).
const std::vector<std::string>& WorldPlacements(const std::string& name);

/// Builds a world by name with a beacon placement and noise. `authors_compat` reproduces the
/// authors' slips in Dynamic 2D and is ignored by Static 2D (which has no reference code).
/// Throws UserError naming the valid worlds (or placements) when a name is unknown.
std::unique_ptr<World> MakeWorld(const std::string& name, const std::string& placement,
                                 double noise_sigma, bool authors_compat);

}  // namespace recon::worlds
