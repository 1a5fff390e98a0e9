#include "engine/worlds/world.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace recon::worlds {

void CheckDemosFillConfigurations(const World& world, int demos, const std::string& option) {
  const int n = world.DemosPerConfiguration();
  if (n <= 1 || demos % n == 0) return;
  const int full = demos / n;
  throw UserError(option + " " + std::to_string(demos) + ": the " + world.Name() +
                  " world records " + std::to_string(n) +
                  " demonstrations per scene configuration, so " + std::to_string(demos) +
                  " would split into " + std::to_string(full) + " full configuration" +
                  (full == 1 ? "" : "s") + " and one with " + std::to_string(demos % n) +
                  " take; give a multiple of " + std::to_string(n) + " (e.g. " +
                  std::to_string(full * n) + " or " + std::to_string((full + 1) * n) + ")");
}

void ResetForDemo(World& world, const std::vector<uint64_t>& seeds, size_t index) {
  const size_t n = static_cast<size_t>(std::max(1, world.DemosPerConfiguration()));
  const size_t configuration = index / n;
  world.ResetTake(seeds[index], seeds[configuration * n], static_cast<int>(configuration));
}

std::vector<float> PerturbAction(const World& world, const std::vector<float>& u, double sigma,
                                 Rng& rng) {
  if (sigma <= 0) return u;
  const std::vector<float> scale = world.ActionNoiseScale();
  if (scale.size() != u.size()) return u;
  std::vector<float> executed = u;
  for (size_t i = 0; i < u.size(); ++i) {
    if (scale[i] != 0) executed[i] += static_cast<float>(sigma * scale[i] * rng.Normal());
  }
  return executed;
}

Dataset RecordDemonstrations(World& world, const std::vector<uint64_t>& seeds,
                             int play_per_scenario, const DemoNoise& noise) {
  if (play_per_scenario < 0) {
    throw UserError("play samples per scenario must be >= 0, got " +
                    std::to_string(play_per_scenario));
  }
  Dataset dataset;
  dataset.spec = world.Spec();
  dataset.demos.reserve(seeds.size());
  dataset.play.reserve(seeds.size() * static_cast<size_t>(play_per_scenario));
  if (!std::isfinite(noise.sigma) || noise.sigma < 0) {
    throw UserError("demonstration noise must be a non-negative number");
  }
  for (size_t index = 0; index < seeds.size(); ++index) {
    ResetForDemo(world, seeds, index);
    Rng noise_rng(Rng::Derive(noise.seed, seeds[index]));
    // Play comes from the initial scenario, before the demonstration moves anything.
    for (int i = 0; i < play_per_scenario; ++i) dataset.play.push_back(world.SamplePlay());
    if (play_per_scenario > 0) dataset.play_chunks.push_back(play_per_scenario);
    Episode episode;
    episode.samples.reserve(world.EpisodeLength());
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      Observation obs = world.Observe();
      Sample sample;
      sample.x = std::move(obs.x);
      sample.y = std::move(obs.y);
      sample.b = world.BeaconReading();
      sample.u = world.ExpertAction();
      world.Step(PerturbAction(world, sample.u, noise.sigma, noise_rng));
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

std::string World::MetricKey() const {
  const WorldTraits traits = Traits();
  if (!traits.metric_key.empty()) return traits.metric_key;
  return traits.higher_is_better ? "reward" : "distance";
}

}  // namespace recon::worlds
