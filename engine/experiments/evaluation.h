#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "engine/learn/learner.h"
#include "engine/worlds/world.h"

namespace recon::experiments {

using WorldMaker = std::function<std::unique_ptr<worlds::World>()>;

/// Rolls `policy` out on each test scenario (one world per scenario, stepped in lockstep so the
/// policy sees all observations of a step in one batch) and returns each scenario's metric.
/// The worlds are made without beacons: a trained policy never reads one.
std::vector<double> EvaluatePolicy(const WorldMaker& make_world, const learn::Policy& policy,
                                   const std::vector<uint64_t>& scenario_seeds);

/// The expert's metric on the same scenarios (the ceiling a figure draws as a reference).
std::vector<double> EvaluateExpert(const WorldMaker& make_world,
                                   const std::vector<uint64_t>& scenario_seeds);

}  // namespace recon::experiments
