#include "engine/worlds/world.h"

#include <string>

#include "engine/core/error.h"

namespace recon::worlds {

Dataset RecordDemonstrations(World& world, const std::vector<uint64_t>& seeds,
                             int play_per_scenario) {
  if (play_per_scenario < 0) {
    throw UserError("play samples per scenario must be >= 0, got " +
                    std::to_string(play_per_scenario));
  }
  Dataset dataset;
  dataset.spec = world.Spec();
  dataset.demos.reserve(seeds.size());
  dataset.play.reserve(seeds.size() * static_cast<size_t>(play_per_scenario));
  for (uint64_t seed : seeds) {
    world.Reset(seed);
    // Play comes from the initial scenario, before the demonstration moves anything.
    for (int i = 0; i < play_per_scenario; ++i) dataset.play.push_back(world.SamplePlay());
    Episode episode;
    episode.samples.reserve(world.EpisodeLength());
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      Observation obs = world.Observe();
      Sample sample;
      sample.x = std::move(obs.x);
      sample.y = std::move(obs.y);
      sample.b = world.BeaconReading();
      sample.u = world.ExpertAction();
      world.Step(sample.u);
      episode.samples.push_back(std::move(sample));
      // A teacher stops recording once the task is done (see World::DemonstrationDone).
      if (world.DemonstrationDone()) break;
    }
    dataset.demos.push_back(std::move(episode));
  }
  return dataset;
}

double Rollout(World& world, uint64_t seed, const PolicyFn& policy) {
  world.Reset(seed);
  for (int t = 0; t < world.EpisodeLength(); ++t) world.Step(policy(world.Observe()));
  return world.EpisodeMetric();
}

}  // namespace recon::worlds
