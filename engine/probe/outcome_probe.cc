#include "engine/probe/outcome_probe.h"

#include <algorithm>
#include <limits>
#include <map>

#include "engine/core/error.h"
#include "engine/core/parallel_for.h"

namespace recon::probe {

namespace {

/// Places rolled out together: one batch per policy step, and the grain of the progress and of
/// a cancel.
constexpr size_t kBatch = 16;

}  // namespace

OutcomeResult ProbeOutcomes(worlds::World& world, uint64_t scene_seed,
                            const std::vector<std::string>& objects, const ProbeGrid& grid,
                            const std::vector<ProbeSubject>& subjects,
                            const ProbeProgress& progress, const std::atomic<bool>* cancel) {
  const ProbedScene scene = SetUpProbe(world, scene_seed, objects, grid, subjects.size());
  if (!world.HasSuccess()) {
    throw UserError("the " + world.Name() +
                    " world's rollouts do not succeed or fail, so there is no outcome to probe");
  }
  for (const ProbeSubject& s : subjects) {
    if (!s.rollouts) throw UserError(s.label + " cannot be rolled out here");
  }
  OutcomeResult result;
  result.scene_seed = scene_seed;
  result.objects = scene.objects;
  result.outcomes.assign(subjects.size(), {});
  const int cells = grid.nx * grid.ny;
  const int total = static_cast<int>(result.objects.size()) * cells;
  for (size_t k = 0; k < result.objects.size(); ++k) {
    const std::string& object = result.objects[k];
    // Places where the task cannot be done at all say nothing of the policy: left out.
    std::vector<GridPlace> places;
    int infeasible = 0;
    for (const GridPlace& place :
         FreePlaces(grid, scene.bounds, scene.area, scene.layout, object)) {
      world.Reset(scene_seed);
      world.PlaceObject(object, place.xy);
      if (world.TaskFeasible()) {
        places.push_back(place);
      } else {
        ++infeasible;
      }
    }
    world.Reset(scene_seed);
    ObjectOutcome empty;
    empty.object = object;
    empty.succeeded.assign(static_cast<size_t>(cells), std::numeric_limits<double>::quiet_NaN());
    empty.places = static_cast<int>(places.size());
    empty.infeasible = infeasible;
    std::vector<ObjectOutcome> outcomes(subjects.size(), empty);
    // The scene as it was: copy 0 of the first batch is left where the scene has it.
    const auto roll = [&](const std::vector<GridPlace>& batch, bool with_home) {
      const size_t copies = batch.size() + (with_home ? 1 : 0);
      RethrowFirst(ParallelForEachCatching(subjects.size(), 2, [&](size_t m) {
        const std::vector<bool> ok =
            subjects[m].rollouts(scene_seed, copies, [&](worlds::World& w, size_t copy) {
              if (with_home && copy == 0) return;
              w.PlaceObject(object, batch[copy - (with_home ? 1 : 0)].xy);
            });
        if (ok.size() != copies) throw UserError(subjects[m].label + ": a rollout went missing");
        size_t at = 0;
        if (with_home) outcomes[m].home_succeeded = ok[at++];
        for (const GridPlace& place : batch) {
          outcomes[m].succeeded[static_cast<size_t>(place.cell)] = ok[at++] ? 1.0 : 0.0;
        }
      }));
    };
    size_t first = 0;
    do {  // at least once: the scene as it was is rolled out with the first batch
      if (cancel != nullptr && cancel->load()) throw ProbeCancelled{};
      const size_t last = std::min(places.size(), first + kBatch);
      roll(std::vector<GridPlace>(places.begin() + static_cast<std::ptrdiff_t>(first),
                                  places.begin() + static_cast<std::ptrdiff_t>(last)),
           first == 0);
      // Progress in grid cells: up to the next place's, or the whole grid after the last batch.
      const int reached = last < places.size() ? places[last].cell : cells;
      if (progress) progress(static_cast<int>(k) * cells + reached, total);
      first = last;
    } while (first < places.size());
    for (size_t m = 0; m < subjects.size(); ++m) {
      int successes = 0;
      for (double v : outcomes[m].succeeded) successes += v == 1.0 ? 1 : 0;
      outcomes[m].success_rate =
          places.empty() ? 0.0
                         : static_cast<double>(successes) / static_cast<double>(places.size());
      result.outcomes[m].push_back(std::move(outcomes[m]));
    }
  }
  world.Reset(scene_seed);  // the scene as it was
  return result;
}

}  // namespace recon::probe
