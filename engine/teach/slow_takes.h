#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace recon::teach {

/// A kept take is slow when it is longer than this many times the median of the other kept takes.
/// The same factor as the rollout horizon (experiments::kRolloutFactor): rollouts run 1.5 times
/// the longest take, so one take this slow stretches every rollout by itself.
inline constexpr double kSlowTakeFactor = 1.5;

/// A demonstration the teacher kept, as the slow-take check reads it.
struct KeptTake {
  std::string name;  ///< e.g. "demo_3"
  int64_t samples = 0;
};

/// The kept takes that are slow (kSlowTakeFactor), in order; none when fewer than two are kept.
std::vector<size_t> SlowTakes(const std::vector<KeptTake>& takes);

/// What to tell the teacher before training when some kept takes are slow, or "" when none is.
/// Why it matters: a policy learns the teacher's pace as well as the route (a take that hesitates
/// teaches hesitation), and the rollouts are given 1.5 times the longest take. `step_s` is the
/// control period (seconds per sample).
std::string SlowTakesWarning(const std::vector<KeptTake>& takes, double step_s);

}  // namespace recon::teach
