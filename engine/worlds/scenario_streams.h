#pragma once

#include <cstdint>

namespace recon::worlds {

// Sub-streams of a scenario's seed (Rng::Derive), shared by every world. The layout (and a 2-D
// world's background) comes from its own stream, so it is the same whatever the placement,
// noise or number of play samples.
constexpr uint64_t kScenarioStream = 0;
constexpr uint64_t kNoiseStream = 1;
constexpr uint64_t kPlayStream = 2;

}  // namespace recon::worlds
