#include "engine/experiments/evaluation.h"

namespace recon::experiments {

std::vector<double> EvaluatePolicy(const WorldMaker& make_world, const learn::Policy& policy,
                                   const std::vector<uint64_t>& scenario_seeds) {
  const size_t n = scenario_seeds.size();
  std::vector<std::unique_ptr<worlds::World>> scenario_worlds;
  scenario_worlds.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    scenario_worlds.push_back(make_world());
    scenario_worlds.back()->Reset(scenario_seeds[i]);
  }
  const int steps = n > 0 ? scenario_worlds.front()->EpisodeLength() : 0;
  std::vector<std::vector<float>> xs(n), ys(n);
  for (int t = 0; t < steps; ++t) {
    for (size_t i = 0; i < n; ++i) {
      worlds::Observation obs = scenario_worlds[i]->Observe();
      xs[i] = std::move(obs.x);
      ys[i] = std::move(obs.y);
    }
    const std::vector<std::vector<float>> actions = policy.ActBatch(xs, ys);
    for (size_t i = 0; i < n; ++i) scenario_worlds[i]->Step(actions[i]);
  }
  std::vector<double> metrics(n);
  for (size_t i = 0; i < n; ++i) metrics[i] = scenario_worlds[i]->EpisodeMetric();
  return metrics;
}

std::vector<double> EvaluateExpert(const WorldMaker& make_world,
                                   const std::vector<uint64_t>& scenario_seeds) {
  std::vector<double> metrics;
  metrics.reserve(scenario_seeds.size());
  std::unique_ptr<worlds::World> world = make_world();
  for (uint64_t seed : scenario_seeds) {
    metrics.push_back(worlds::Rollout(
        *world, seed, [&](const worlds::Observation&) { return world->ExpertAction(); }));
  }
  return metrics;
}

}  // namespace recon::experiments
