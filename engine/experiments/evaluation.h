#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/learner.h"
#include "engine/worlds/world.h"

namespace recon::experiments {

using WorldMaker = std::function<std::unique_ptr<worlds::World>()>;

/// How a policy did on one test scenario.
struct ScenarioOutcome {
  double metric = 0;
  bool succeeded = false;  ///< only meaningful for worlds with HasSuccess()
  /// World::OutcomeDetails() at the end; with a feature gate also the mean gate over the
  /// episode (feature_gate) and, in worlds that report "grasped", before and after the first
  /// grasp (feature_gate_before_grasp, feature_gate_after_grasp: what the policy looked at).
  std::map<std::string, double> details;
  /// World::ReplayState() after the reset and after each step (EpisodeLength() + 1 states), to
  /// play the rollout back; empty unless asked for, and for worlds without a replay or that
  /// ScoresActions() (whose rollout is the expert's, not the policy's).
  std::vector<std::vector<double>> replay;
};

/// What a caller that shows a rollout's progress, or may stop it, hands EvaluatePolicy. Neither
/// changes the rollout.
struct EvaluationHooks {
  /// Called after each step of the batch with the steps done and the episode's length.
  std::function<void(int done, int steps)> on_step;
  /// Checked before each step; once true, EvaluatePolicy throws EvaluationCancelled.
  const std::atomic<bool>* cancel = nullptr;
};

/// A rollout stopped because it was asked to (EvaluationHooks::cancel); nothing was scored.
class EvaluationCancelled : public UserError {
 public:
  using UserError::UserError;
};

/// Sets a test scenario's world up after its reset and before the first step (the outcome probe
/// moves an object there); unlike EvaluationHooks, it changes the rollout.
using ScenarioArrangement = std::function<void(worlds::World& world, size_t scenario)>;

/// Scores `policy` on each test scenario, one world per scenario stepped in lockstep so the
/// policy sees all observations of a step in one batch. Usually the policy drives (a rollout) and
/// the world's EpisodeMetric scores the end state; for worlds that ScoresActions(), the expert
/// drives and the metric is the mean squared difference between the policy's and the expert's
/// actions over the demonstration (mean over steps and action components).
/// The worlds are made without beacons: a trained policy never reads one. `keep_replay` fills
/// each outcome's replay; it changes nothing else. `arrange`, when given, is called on each
/// scenario's world after its reset.
/// `steps` > 0 rolls out that many steps instead of the world's EpisodeLength() (RolloutSteps).
std::vector<ScenarioOutcome> EvaluatePolicy(
    const WorldMaker& make_world, const learn::Policy& policy,
    const std::vector<uint64_t>& scenario_seeds, bool keep_replay = false,
    const EvaluationHooks& hooks = {}, const ScenarioArrangement& arrange = nullptr, int steps = 0);

/// A rollout may take at most this many times the world's episode, however long the takes.
constexpr double kMaxRolloutFactor = 4.0;
/// Rollouts are given this many times the longest demonstration (RolloutSteps).
constexpr double kRolloutFactor = 1.5;

/// How long a policy taught by these demonstrations is given: the world's episode
/// (EpisodeLength) or `factor` times the longest demonstration (samples), whichever is longer, a
/// slow teacher's policy being as slow; at most kMaxRolloutFactor times the world's episode.
/// `note`, when given, says why when the demonstrations asked for more than that (an absurd
/// take, e.g. one left running for minutes).
int RolloutSteps(const worlds::World& world, const std::vector<int64_t>& demo_samples,
                 double factor = kRolloutFactor, std::string* note = nullptr);

/// The expert's outcome on the same scenarios (the ceiling a figure draws as a reference; 0 for
/// worlds that ScoresActions()).
std::vector<ScenarioOutcome> EvaluateExpert(const WorldMaker& make_world,
                                            const std::vector<uint64_t>& scenario_seeds);

/// The metrics of some outcomes, and the fraction that succeeded.
std::vector<double> Metrics(const std::vector<ScenarioOutcome>& outcomes);
double SuccessRate(const std::vector<ScenarioOutcome>& outcomes);
/// The mean of each detail over the outcomes that report it.
std::map<std::string, double> MeanDetails(const std::vector<ScenarioOutcome>& outcomes);

}  // namespace recon::experiments
