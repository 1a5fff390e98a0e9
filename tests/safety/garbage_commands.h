#pragma once

#include <array>
#include <cmath>

#include "engine/core/rng.h"

namespace recon::safety::testing {

/// The mix of a policy gone wrong: per joint, NaN while a uniform draw is below `nan_below`,
/// a huge value in +-huge while it is below `huge_below`, otherwise a plain one in +-plain.
struct GarbageMix {
  double nan_below = 0.1;
  double huge_below = 0.4;
  double huge = 1e9;
  double plain = 2.0;
};

/// One joint velocity command of garbage, drawn from `rng` (so a seed reproduces the run).
inline std::array<double, 6> GarbageJointVelocities(Rng& rng, const GarbageMix& mix) {
  std::array<double, 6> v;
  for (double& x : v) {
    const double kind = rng.Uniform(0, 1);
    x = kind < mix.nan_below    ? std::nan("")
        : kind < mix.huge_below ? rng.Uniform(-mix.huge, mix.huge)
                                : rng.Uniform(-mix.plain, mix.plain);
  }
  return v;
}

}  // namespace recon::safety::testing
