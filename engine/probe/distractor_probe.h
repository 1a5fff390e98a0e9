#pragma once

// The distractor probe: what a trained policy looks at, found by moving one object at a time
// over a grid of table places with everything else held, and measuring how much the features
// phi and the policy's action change. RECON should move with the plate (what its beacon marked)
// and not with the bowl (what the Baseline confuses it with).

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/probe/probe_grid.h"
#include "engine/worlds/world.h"

namespace recon::probe {

/// What is probed: a trained method's actions and features for a batch of observations (one
/// row each). A learn::Policy gives them (PolicySubject); a test can give a policy it made by
/// hand, whose answer is known.
struct ProbeSubject {
  std::string method;  ///< "baseline", "recon", ...
  std::string label;   ///< for people: "RECON (Play)"
  using Rows = std::vector<std::vector<float>>;
  std::function<Rows(const Rows&xs, const Rows&ys)> act, features;
  /// Sets one copy of the scene up after its reset (the outcome probe moves an object there).
  using Arrangement = std::function<void(worlds::World& world, size_t copy)>;
  /// Whole rollouts from `copies` copies of the scene `scene_seed`, each set up by `arrange`:
  /// whether each succeeded. Only the outcome probe (outcome_probe.h) asks for them.
  std::function<std::vector<bool>(uint64_t scene_seed, size_t copies, const Arrangement& arrange)>
      rollouts;
};

/// One object probed for one method.
struct ObjectProbe {
  std::string object;
  std::array<double, 2> home = {0, 0};  ///< where the scene had it (table x, y)
  std::array<double, 4> bounds = {0, 0, 0, 0};
  int nx = 0, ny = 0;
  /// Per grid cell (row-major, y rows from y_min, x columns from x_min): |a(p) - a(home)| and
  /// |phi(p) - phi(home)|; NaN where the object would overlap another.
  std::vector<double> action_change, feature_change;
  /// The changes per 10 cm of the object's motion, averaged over the cells at least 2 cm from
  /// home: "action change per 10 cm of bowl motion".
  double action_change_per_10cm = 0, feature_change_per_10cm = 0;
};

/// Every method's probes, per object, of one scene.
struct ProbeResult {
  uint64_t scene_seed = 0;
  std::vector<std::string> objects;
  /// [method index][object index], methods in the order given.
  std::vector<std::vector<ObjectProbe>> probes;
  std::vector<std::string> methods, labels;
};

/// Progress: grid places rendered so far of all.
using ProbeProgress = std::function<void(int done, int total)>;

/// Thrown when `cancel` was raised; nothing of the probe is kept.
struct ProbeCancelled {};

/// Probes `objects` (all of ObjectLayout's when empty) of the scene `scene_seed` of `world`,
/// each method on the same rendered observations. The world is Reset to the scene before each
/// object. UserError, before any rendering, for a world that cannot move its objects, an object
/// it does not have (naming the valid ones), a grid of fewer than 2 x 2 or more than 100 x 100
/// places, or bounds that leave the table (naming its extent) or are empty.
ProbeResult ProbeObjects(worlds::World& world, uint64_t scene_seed,
                         const std::vector<std::string>& objects, const ProbeGrid& grid,
                         const std::vector<ProbeSubject>& subjects,
                         const ProbeProgress& progress = nullptr,
                         const std::atomic<bool>* cancel = nullptr);

}  // namespace recon::probe
