#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/experiments/condition.h"
#include "engine/learn/learner.h"
#include "engine/worlds/world_factory.h"

namespace recon::experiments {

/// A paper experiment as data: which world, which conditions, how many demonstrations, runs and
/// test scenarios, and the training recipe.
struct ExperimentConfig {
  std::string world;  ///< "dynamic2d" | "static2d"
  std::vector<Condition> conditions;
  std::vector<int> demos = {10};  ///< several values sweep data efficiency
  int runs = 15;                  ///< independent training runs per condition and demo count
  int tests = 100;                ///< test scenarios, shared by every condition and run
  uint64_t seed = 1;              ///< everything random derives from this (see SeedsOf* below)
  bool authors_compat = false;    ///< reproduce the authors' two Dynamic 2D slips
  int jobs = 2;                   ///< runs trained in parallel, one Torch thread each
  /// Renders camera images for the simulated cell's image worlds (tabletop); set by the app.
  worlds::CellResources cell;
  learn::NetworkConfig network;
  learn::TrainConfig train;   ///< method, seed and steps are set per condition and run
  int baseline_steps = 3001;  ///< the authors train the Baseline for half as long
  /// Play samples recorded per demonstration scenario for conditions that use play; -1 takes
  /// the world's own recipe (World::PlaySamplesPerScenario).
  int play_per_scenario = -1;
  /// Noise injected into the executed actions while the demonstrations are recorded (DART,
  /// worlds::DemoNoise), in the action's units; 0 = off.
  double demo_noise = 0.0;
  /// Models trained per run from different training seeds, acting as one (learn::Policy::
  /// Ensemble): model 0 from the run's training seed, model m from Rng::Derive(it, m). 1 = one
  /// model (the paper's); at most kMaxPolicyEnsemble.
  int policy_ensemble = 1;
  /// Who gives the demonstrations: "expert" (the world's scripted teacher) or "person" (the
  /// tabletop's simulated person at the keyboard, teach::SimulatedPerson: human-paced takes
  /// with pauses, overshoot and missed grasps, a failed take recorded again).
  std::string teacher = "expert";
  /// When not empty, the demonstrations' pauses are left out of training, both methods alike
  /// (WithoutPauses, engine/core/pauses.h), with these action entries as motion
  /// (WorldRecipe::pause_motion); empty: every sample is trained on.
  std::vector<float> pause_motion;
};

/// Demonstration teachers an experiment accepts.
const std::vector<std::string>& ExperimentTeachers();

/// The largest ExperimentConfig::policy_ensemble accepted.
constexpr int kMaxPolicyEnsemble = 16;

/// The outcome of one training run of one condition.
struct RunResult {
  std::string condition;
  int demos = 0;
  int run = 0;
  uint64_t data_seed = 0;    ///< seeds the run's demonstration scenarios
  uint64_t train_seed = 0;   ///< seeds initialisation, batches and sampling noise
  double metric = 0;         ///< mean episode metric over the test scenarios
  double success_rate = 0;   ///< fraction of test scenarios solved (worlds with HasSuccess())
  bool has_success = false;  ///< ExperimentResult::has_success: success_rate means something
  std::map<std::string, double> details;  ///< World::OutcomeDetails() means over test scenarios
  int64_t demo_samples = 0;  ///< samples in the run's demonstrations (they may stop early)
  int attempts = 1;
  int train_steps = 0;
  double train_seconds = 0;
  learn::StepMetrics final_losses;
};

/// A condition's action loss over training (run 0), averaged in windows, for the loss figure.
struct LossCurve {
  std::string condition;
  int demos = 0;
  std::vector<double> step;
  std::vector<double> action_loss;
};

struct ExperimentResult {
  std::vector<RunResult> runs;  ///< in (demos, condition, run) order
  std::vector<LossCurve> loss_curves;
  double wall_seconds = 0;
  std::string metric_name;
  bool higher_is_better = true;
  double expert_metric = 0;  ///< the expert's mean score on the test scenarios
  std::string metric_key;    ///< the metric's short name in summary.json, e.g. "distance"
  bool has_success = false;  ///< the world reports success (runs carry a success rate)
  double step_seconds = 0;   ///< World::StepSeconds(): > 0 makes a teaching-time ledger
  int episode_length = 0;
  int play_per_scenario = 0;  ///< play samples per demonstration scenario actually used
  double expert_success_rate = 0;
};

/// Seed of scenario `index` of run `run`'s demonstrations. A run with 5 demos uses a prefix of
/// the scenarios of the same run with 10, so a data-efficiency sweep adds data, never swaps it.
uint64_t DemoScenarioSeed(uint64_t seed, int run, int index);
/// Seed of the learner's randomness in run `run` (the same for every condition: paired runs).
uint64_t TrainSeed(uint64_t seed, int run);
/// Seed of test scenario `index` (the same for every condition and run).
uint64_t TestScenarioSeed(uint64_t seed, int index);
/// Seed of the noise injected into run `run`'s demonstrations (ExperimentConfig::demo_noise).
uint64_t DemoNoiseSeed(uint64_t seed, int run);

/// Steps a condition trains for: the Baseline has its own count (the authors halve it).
int TrainSteps(const ExperimentConfig& config, const Condition& condition);

/// Checks the configuration as far as it can without training: counts, steps, and for every
/// RECON condition that the feature size k exceeds its beacon dimension d. Throws UserError.
void ValidateExperimentConfig(const ExperimentConfig& config);

/// One independent piece of an experiment: one training run of one condition at one
/// demonstration count, trained and rolled out on its own (on this machine, or as a task of a
/// cluster's job array: sweep_plan.h).
struct ExperimentUnit {
  int index = 0;  ///< in the plan's order
  int demos = 0;
  size_t condition = 0;  ///< into ExperimentConfig::conditions
  int run = 0;
};

/// Every unit of `config`, run-major (run, then demos, then condition): stopped early, every
/// condition has the same runs done.
std::vector<ExperimentUnit> PlanUnits(const ExperimentConfig& config);

/// What a unit gives: its run, and for run 0 the condition's action loss over training.
struct UnitResult {
  ExperimentUnit unit;
  RunResult run;
  std::optional<LossCurve> curve;
};

/// Trains and rolls out one unit. The same bytes of result whichever machine or order runs it
/// (on the same CPU kind), but for run.train_seconds. UserError "cancelled" when *cancel
/// becomes true.
UnitResult RunUnit(const ExperimentConfig& config, const ExperimentUnit& unit,
                   const std::atomic<bool>* cancel = nullptr);

/// What an experiment's table says of its world and expert, before any unit: the metric, the
/// expert's score on the test scenarios, the episode's length... (ExperimentResult without runs,
/// curves or wall time).
ExperimentResult DescribeExperiment(const ExperimentConfig& config);

/// `described` with the units' runs in (demos, condition, run) order and run 0's curves, in the
/// order RunExperiment returns them. Units may be missing (a sweep collected part way).
ExperimentResult AssembleExperiment(const ExperimentConfig& config, ExperimentResult described,
                                    const std::vector<UnitResult>& units);

/// Called once per finished run (from worker threads, serialised by the runner).
using RunObserver = std::function<void(const RunResult&)>;

/// Trains every condition for every run and demo count (in parallel, `jobs` at a time), rolls each
/// trained policy out on the same test scenarios without beacons, and returns the table. Stops
/// early (and throws UserError "cancelled") when *cancel becomes true.
ExperimentResult RunExperiment(const ExperimentConfig& config, const RunObserver& on_run = {},
                               const std::atomic<bool>* cancel = nullptr);

}  // namespace recon::experiments
