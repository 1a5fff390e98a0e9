#include "engine/experiments/evaluation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/learn/action_ensembler.h"

namespace recon::experiments {

namespace {

double SquaredError(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (size_t k = 0; k < a.size(); ++k) {
    const double d = static_cast<double>(a[k]) - b[k];
    sum += d * d;
  }
  return a.empty() ? 0.0 : sum / static_cast<double>(a.size());
}

}  // namespace

std::vector<ScenarioOutcome> EvaluatePolicy(const WorldMaker& make_world,
                                            const learn::Policy& policy,
                                            const std::vector<uint64_t>& scenario_seeds,
                                            bool keep_replay, const EvaluationHooks& hooks,
                                            const ScenarioArrangement& arrange, int steps) {
  const size_t n = scenario_seeds.size();
  std::vector<std::unique_ptr<worlds::World>> scenario_worlds;
  scenario_worlds.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    scenario_worlds.push_back(make_world());
    scenario_worlds.back()->Reset(scenario_seeds[i]);
    if (arrange) arrange(*scenario_worlds.back(), i);
  }
  if (n == 0) return {};
  const bool score_actions = scenario_worlds.front()->ScoresActions();
  if (steps <= 0) steps = scenario_worlds.front()->EpisodeLength();
  std::vector<ScenarioOutcome> outcomes(n);
  // ReplayState() only reads the world, so keeping it cannot change the rollout.
  const bool replay =
      keep_replay && !score_actions && !scenario_worlds.front()->ReplayState().empty();
  const auto keep_frame = [&] {
    for (size_t i = 0; i < n; ++i) outcomes[i].replay.push_back(scenario_worlds[i]->ReplayState());
  };
  if (replay) {
    for (ScenarioOutcome& o : outcomes) o.replay.reserve(static_cast<size_t>(steps) + 1);
    keep_frame();
  }
  std::vector<std::vector<float>> xs(n), ys(n);
  std::vector<double> action_error(n, 0.0);
  // What the feature gate let through (NetworkConfig::feature_gate_hidden), per scenario and
  // phase (0 before the first grasp, 1 after).
  const bool gated = policy.has_feature_gate() && !score_actions;
  std::vector<float> gates;
  std::vector<std::array<double, 2>> gate_sum(n, {0.0, 0.0});
  std::vector<std::array<int, 2>> gate_steps(n, {0, 0});
  // A policy that predicts chunks of actions acts on their running ensemble (ACT).
  const int chunk = policy.action_chunk();
  std::vector<learn::ActionEnsembler> ensemblers;
  if (chunk > 1) {
    ensemblers.assign(
        n, learn::ActionEnsembler(chunk, policy.spec().u_dim, 0.01, policy.ensembled_actions()));
  }
  for (int t = 0; t < steps; ++t) {
    if (hooks.cancel != nullptr && hooks.cancel->load()) {
      throw EvaluationCancelled("the rollouts were cancelled at step " + std::to_string(t) +
                                " of " + std::to_string(steps));
    }
    for (size_t i = 0; i < n; ++i) {
      worlds::Observation obs = scenario_worlds[i]->Observe();
      xs[i] = std::move(obs.x);
      ys[i] = std::move(obs.y);
    }
    std::vector<std::vector<float>> actions;
    if (chunk > 1) {
      actions = policy.ActChunkBatch(xs, ys, gated ? &gates : nullptr);
      for (size_t i = 0; i < n; ++i) actions[i] = ensemblers[i].Step(actions[i]);
    } else {
      actions = policy.ActBatch(xs, ys, gated ? &gates : nullptr);
    }
    if (gated) {
      for (size_t i = 0; i < n; ++i) {
        // Before and after the world's first grasp, where it has one ("grasped" in its details).
        const auto details = scenario_worlds[i]->OutcomeDetails();
        const auto grasped = details.find("grasped");
        const int phase = grasped != details.end() && grasped->second > 0 ? 1 : 0;
        gate_sum[i][phase] += gates[i];
        ++gate_steps[i][phase];
      }
    }
    for (size_t i = 0; i < n; ++i) {
      if (score_actions) {
        const std::vector<float> expert = scenario_worlds[i]->ExpertAction();
        action_error[i] += SquaredError(actions[i], expert);
        scenario_worlds[i]->Step(expert);
      } else {
        scenario_worlds[i]->Step(actions[i]);
      }
    }
    if (replay) keep_frame();
    if (hooks.on_step) hooks.on_step(t + 1, steps);
  }
  for (size_t i = 0; i < n; ++i) {
    outcomes[i].metric =
        score_actions ? action_error[i] / steps : scenario_worlds[i]->EpisodeMetric();
    outcomes[i].succeeded = scenario_worlds[i]->TaskSucceeded();
    if (!score_actions) outcomes[i].details = scenario_worlds[i]->OutcomeDetails();
    if (gated) {
      std::map<std::string, double>& d = outcomes[i].details;
      d["feature_gate"] = (gate_sum[i][0] + gate_sum[i][1]) / steps;
      if (d.count("grasped") > 0) {
        // A scenario that never grasped has no "after", and reports none.
        if (gate_steps[i][0] > 0)
          d["feature_gate_before_grasp"] = gate_sum[i][0] / gate_steps[i][0];
        if (gate_steps[i][1] > 0) d["feature_gate_after_grasp"] = gate_sum[i][1] / gate_steps[i][1];
      }
    }
  }
  return outcomes;
}

int RolloutSteps(const worlds::World& world, const std::vector<int64_t>& demo_samples,
                 double factor, std::string* note) {
  const int episode = world.EpisodeLength();
  // Worlds whose rollouts score a fixed number of steps (the paper's 10-step 2-D tasks) or the
  // expert's actions keep their episode: only a task that is done or not has a horizon to fit.
  if (!world.HasSuccess() || world.ScoresActions()) return episode;
  int64_t longest = 0;
  for (int64_t samples : demo_samples) longest = std::max(longest, samples);
  const double wanted = std::ceil(factor * static_cast<double>(longest));
  const int cap = static_cast<int>(kMaxRolloutFactor * episode);
  if (wanted > cap && note != nullptr) {
    const double step_s = world.StepSeconds() > 0 ? world.StepSeconds() : 1.0;
    char text[256];
    std::snprintf(text, sizeof(text),
                  "the longest demonstration (%.1f s) would give rollouts of %.0f s; they are "
                  "held to %.0f s (%g times the world's %.0f s)",
                  static_cast<double>(longest) * step_s, wanted * step_s, cap * step_s,
                  kMaxRolloutFactor, episode * step_s);
    *note = text;
  }
  return static_cast<int>(std::clamp<double>(wanted, episode, cap));
}

std::vector<ScenarioOutcome> EvaluateExpert(const WorldMaker& make_world,
                                            const std::vector<uint64_t>& scenario_seeds) {
  std::vector<ScenarioOutcome> outcomes;
  outcomes.reserve(scenario_seeds.size());
  std::unique_ptr<worlds::World> world = make_world();
  for (uint64_t seed : scenario_seeds) {
    const double metric = worlds::Rollout(
        *world, seed, [&](const worlds::Observation&) { return world->ExpertAction(); });
    ScenarioOutcome outcome;
    outcome.metric = world->ScoresActions() ? 0.0 : metric;
    outcome.succeeded = world->TaskSucceeded();
    outcomes.push_back(std::move(outcome));
  }
  return outcomes;
}

std::vector<double> Metrics(const std::vector<ScenarioOutcome>& outcomes) {
  std::vector<double> metrics;
  metrics.reserve(outcomes.size());
  for (const ScenarioOutcome& o : outcomes) metrics.push_back(o.metric);
  return metrics;
}

double SuccessRate(const std::vector<ScenarioOutcome>& outcomes) {
  if (outcomes.empty()) return 0.0;
  int succeeded = 0;
  for (const ScenarioOutcome& o : outcomes) succeeded += o.succeeded ? 1 : 0;
  return static_cast<double>(succeeded) / static_cast<double>(outcomes.size());
}

std::map<std::string, double> MeanDetails(const std::vector<ScenarioOutcome>& outcomes) {
  // Over the scenarios that report each detail (feature_gate_after_grasp only exists after a
  // grasp): a missing value is not a zero.
  std::map<std::string, double> sums;
  std::map<std::string, int> counts;
  for (const ScenarioOutcome& o : outcomes) {
    for (const auto& [key, value] : o.details) {
      sums[key] += value;
      ++counts[key];
    }
  }
  for (auto& [key, sum] : sums) sum /= static_cast<double>(counts[key]);
  return sums;
}

}  // namespace recon::experiments
