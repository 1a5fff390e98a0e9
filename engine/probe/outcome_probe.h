#pragma once

// The distractor probe by outcome: each object moved over the grid of table places, everything
// else held, and a whole rollout of each method from each place. Slower than the first-step
// probe (distractor_probe.h) by the episode's length, and it answers the question a teacher
// cares about: does the robot still do the task when the bowl stands somewhere else?

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/probe/distractor_probe.h"

namespace recon::probe {

/// One object's rollouts for one method.
struct ObjectOutcome {
  std::string object;
  /// Per grid cell (row-major from y_min): 1 where the rollout succeeded, 0 where it failed, NaN
  /// where the object would overlap another or the task cannot be done at all (World::
  /// TaskFeasible: e.g. the plate out of the arm's reach).
  std::vector<double> succeeded;
  double success_rate = 0;      ///< over the places rolled out from
  int places = 0;               ///< rolled out from
  int infeasible = 0;           ///< free places skipped because the task cannot be done there
  bool home_succeeded = false;  ///< the scene as it was
};

struct OutcomeResult {
  uint64_t scene_seed = 0;
  std::vector<std::string> objects;
  /// [method index][object index], methods in the order given.
  std::vector<std::vector<ObjectOutcome>> outcomes;
};

/// Rolls each subject (which must have `rollouts`) out from scene `scene_seed` with each of
/// `objects` (all of ObjectLayout's when empty) at each free, feasible place of `grid`, the
/// methods side by side. Progress counts grid places of all objects; ProbeCancelled between
/// batches of places when `cancel` is raised. UserError as ProbeObjects, and for a world whose
/// rollouts cannot succeed or fail (World::HasSuccess).
OutcomeResult ProbeOutcomes(worlds::World& world, uint64_t scene_seed,
                            const std::vector<std::string>& objects, const ProbeGrid& grid,
                            const std::vector<ProbeSubject>& subjects,
                            const ProbeProgress& progress = nullptr,
                            const std::atomic<bool>* cancel = nullptr);

}  // namespace recon::probe
