#include "engine/experiments/experiment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/pauses.h"
#include "engine/core/rng.h"
#include "engine/core/stats.h"
#include "engine/core/strings.h"
#include "engine/experiments/evaluation.h"
#include "engine/teach/person_takes.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/world_factory.h"

namespace recon::experiments {

namespace {

// Stream numbers keep the three kinds of seeds apart (Rng::Derive).
constexpr uint64_t kDemoStream = 1000;
constexpr uint64_t kTrainStream = 2000;
constexpr uint64_t kTestStream = 3000;
constexpr uint64_t kDemoNoiseStream = 4000;
constexpr uint64_t kPersonStream = 5000;
// Loss curves are averaged over windows so that a figure shows about this many points.
constexpr int kLossCurvePoints = 120;

}  // namespace

int TrainSteps(const ExperimentConfig& config, const Condition& condition) {
  return condition.method == learn::Method::kBaseline ? config.baseline_steps : config.train.steps;
}

void ValidateExperimentConfig(const ExperimentConfig& config) {
  if (config.conditions.empty()) throw UserError("no conditions to run");
  if (config.demos.empty()) throw UserError("--demos needs at least one value");
  for (int d : config.demos) {
    if (d <= 0) throw UserError("--demos must be positive (got " + std::to_string(d) + ")");
  }
  if (config.runs <= 0) throw UserError("--runs must be positive");
  if (config.policy_ensemble < 1 || config.policy_ensemble > kMaxPolicyEnsemble) {
    throw UserError("--policy-ensemble must be between 1 and " +
                    std::to_string(kMaxPolicyEnsemble) + " models (got " +
                    std::to_string(config.policy_ensemble) + ")");
  }
  if (config.tests <= 0) throw UserError("--tests must be positive");
  if (config.jobs <= 0) throw UserError("--jobs must be positive");
  if (config.play_per_scenario < -1) throw UserError("--play must not be negative");
  if (config.train.steps <= 0 || config.baseline_steps <= 0) {
    throw UserError("--steps and --baseline-steps must be positive");
  }
  for (const auto& [weight, option] :
       {std::pair{config.train.beacon_weight, "--beacon-weight"},
        std::pair{config.train.play_weight, "--play-weight"},
        std::pair{config.train.action_weight, "the action weight"}}) {
    if (!std::isfinite(weight) || weight < 0) {
      throw UserError(std::string(option) + " must be a finite number >= 0 (got " +
                      FormatNumber(weight) + ")");
    }
  }
  if (!std::isfinite(config.train.feature_noise) || config.train.feature_noise < 0 ||
      config.train.feature_noise > learn::kMaxFeatureNoise) {
    throw UserError("--feature-noise must be between 0 and " +
                    FormatNumber(learn::kMaxFeatureNoise) +
                    " (standard deviations of each feature; got " +
                    FormatNumber(config.train.feature_noise) + ")");
  }
  if (!std::isfinite(config.train.play_consistency) || config.train.play_consistency < 0 ||
      config.train.play_consistency > learn::kMaxPlayConsistency) {
    throw UserError("--play-consistency must be between 0 and " +
                    FormatNumber(learn::kMaxPlayConsistency) + " (got " +
                    FormatNumber(config.train.play_consistency) + ")");
  }
  if (!std::isfinite(config.train.nll_min_std) || config.train.nll_min_std < 0 ||
      config.train.nll_min_std > learn::kMaxNllMinStd) {
    throw UserError("--nll-min-std must be between 0 and " + FormatNumber(learn::kMaxNllMinStd) +
                    " (got " + FormatNumber(config.train.nll_min_std) + ")");
  }
  if (!std::isfinite(config.demo_noise) || config.demo_noise < 0 ||
      config.demo_noise > worlds::kMaxDemoNoise) {
    throw UserError("--demo-noise must be between 0 and " + FormatNumber(worlds::kMaxDemoNoise) +
                    " (action units, rad/s for the arm; got " + FormatNumber(config.demo_noise) +
                    ")");
  }
  {
    const std::unique_ptr<worlds::World> probe =
        worlds::MakeWorld(config.world, "none", 0.0, config.authors_compat, config.cell);
    for (int d : config.demos) worlds::CheckDemosFillConfigurations(*probe, d, "--demos");
  }
  for (const Condition& c : config.conditions) {
    const int d = worlds::MakeWorld(config.world, c.placement, c.noise_sigma, config.authors_compat,
                                    config.cell)
                      ->Spec()
                      .b_dim;
    if (c.method == learn::Method::kRecon && config.network.feature_dim <= d) {
      throw UserError("condition '" + c.name +
                      "': feature size k=" + std::to_string(config.network.feature_dim) +
                      " must exceed the beacon dimension d=" + std::to_string(d) +
                      " (RECON needs k > d; raise --feature-dim)");
    }
  }
}

uint64_t DemoScenarioSeed(uint64_t seed, int run, int index) {
  return Rng::Derive(Rng::Derive(seed, kDemoStream + run), index);
}

uint64_t TrainSeed(uint64_t seed, int run) { return Rng::Derive(seed, kTrainStream + run); }

uint64_t DemoNoiseSeed(uint64_t seed, int run) { return Rng::Derive(seed, kDemoNoiseStream + run); }

uint64_t TestScenarioSeed(uint64_t seed, int index) {
  return Rng::Derive(Rng::Derive(seed, kTestStream), index);
}

const std::vector<std::string>& ExperimentTeachers() {
  static const std::vector<std::string> teachers = {"expert", "person"};
  return teachers;
}

namespace {

using teach::PersonTakeStats;

/// A run's demonstrations by the configured teacher.
Dataset RecordRunDemonstrations(const ExperimentConfig& config, worlds::World& world,
                                const std::vector<uint64_t>& scenario_seeds, int play, int run,
                                PersonTakeStats* person_stats) {
  if (config.teacher == "expert") {
    return worlds::RecordDemonstrations(world, scenario_seeds, play,
                                        {config.demo_noise, DemoNoiseSeed(config.seed, run)});
  }
  if (config.teacher != "person") {
    throw UserError("unknown demonstration teacher '" + config.teacher +
                    "' (valid: " + JoinNames(ExperimentTeachers()) + ")");
  }
  auto* tabletop = dynamic_cast<worlds::Tabletop*>(&world);
  if (tabletop == nullptr) {
    throw UserError("the simulated person teaches the tabletop only, not " + world.Name());
  }
  return teach::RecordPersonDemonstrations(*tabletop, scenario_seeds, play,
                                           Rng::Derive(config.seed, kPersonStream + run), {}, 5,
                                           person_stats);
}

/// Trains and evaluates one (condition, demos, run). Thread-safe: touches only its own objects.
RunResult RunOne(const ExperimentConfig& config, const ExperimentUnit& task,
                 const std::vector<uint64_t>& test_seeds, LossCurve* curve,
                 const std::atomic<bool>* cancel) {
  const Condition& condition = config.conditions[task.condition];
  std::unique_ptr<worlds::World> world = worlds::MakeWorld(
      config.world, condition.placement, condition.noise_sigma, config.authors_compat, config.cell);

  RunResult result;
  result.condition = condition.name;
  result.demos = task.demos;
  result.run = task.run;
  result.data_seed = Rng::Derive(config.seed, kDemoStream + task.run);
  result.train_seed = TrainSeed(config.seed, task.run);

  std::vector<uint64_t> scenario_seeds;
  for (int i = 0; i < task.demos; ++i) {
    scenario_seeds.push_back(DemoScenarioSeed(config.seed, task.run, i));
  }
  const int play_recipe =
      config.play_per_scenario >= 0 ? config.play_per_scenario : world->PlaySamplesPerScenario();
  const int play = condition.use_play ? play_recipe : 0;
  teach::PersonTakeStats person_stats;
  Dataset data =
      RecordRunDemonstrations(config, *world, scenario_seeds, play, task.run, &person_stats);
  // The horizon follows the takes as the teacher gave them, pauses and all.
  std::vector<int64_t> demo_lengths;
  for (const Episode& e : data.demos)
    demo_lengths.push_back(static_cast<int64_t>(e.samples.size()));
  // A person's pauses go; the scripted teacher's commands that move nothing are its waits.
  if (config.teacher == "person" && !config.pause_motion.empty()) {
    data = WithoutPauses(data, config.pause_motion);
  }
  result.demo_samples = data.NumDemoSamples();

  learn::TrainConfig train = config.train;
  train.method = condition.method;
  train.seed = result.train_seed;
  train.steps = TrainSteps(config, condition);
  learn::Trainer trainer(data, config.network, train);
  if (curve != nullptr) {
    curve->condition = condition.name;
    curve->demos = task.demos;
    const int window = std::max(1, train.steps / kLossCurvePoints);
    trainer.SetObserver([curve, window, sum = 0.0, count = 0](const learn::StepMetrics& m) mutable {
      if (m.step == 0) {  // a restart begins a fresh curve
        curve->step.clear();
        curve->action_loss.clear();
        sum = 0.0;
        count = 0;
      }
      sum += m.action_loss;
      if (++count == window) {
        curve->step.push_back(m.step + 1 - window / 2);
        curve->action_loss.push_back(sum / count);
        sum = 0.0;
        count = 0;
      }
    });
  }

  const auto start = std::chrono::steady_clock::now();
  std::vector<learn::Policy> members;
  try {
    const learn::TrainResult trained = trainer.Train(cancel);
    result.attempts = trained.attempts;
    result.train_steps = trained.steps_run;
    result.final_losses = trained.final_metrics;
    if (trained.cancelled) throw UserError("cancelled");
    members.push_back(trainer.policy());
    // The ensemble's other models: the same data, their own seeds (the first model's losses
    // and steps are the ones reported).
    for (int m = 1; m < config.policy_ensemble; ++m) {
      learn::TrainConfig member_train = train;
      member_train.seed = Rng::Derive(train.seed, static_cast<uint64_t>(m));
      learn::Trainer member(data, config.network, member_train);
      if (member.Train(cancel).cancelled) throw UserError("cancelled");
      members.push_back(member.policy());
    }
  } catch (const DivergenceError& e) {
    // A diverged run is an outcome of this seed, not a reason to lose the whole sweep: it is
    // recorded with a NaN metric, counted in the summary, and left out of the means.
    result.metric = std::nan("");
    result.train_steps = e.step();
    result.train_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  result.train_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const learn::Policy policy = learn::Policy::Ensemble(members);
  const WorldMaker make_test_world = [&] {
    return worlds::MakeWorld(config.world, "none", 0.0, config.authors_compat, config.cell);
  };
  const int rollout_steps = RolloutSteps(*world, demo_lengths);
  const std::vector<ScenarioOutcome> outcomes =
      EvaluatePolicy(make_test_world, policy, test_seeds, false, {}, nullptr, rollout_steps);
  result.metric = Mean(Metrics(outcomes));
  result.success_rate = SuccessRate(outcomes);
  result.details = MeanDetails(outcomes);
  if (config.teacher == "person") {
    // What the person's takes cost and looked like: the teacher's side of the ledger.
    const PersonTakeStats& p = person_stats;
    result.details["teacher_tries_per_demo"] =
        static_cast<double>(p.tries) / std::max(1, p.demonstrations);
    result.details["teacher_seconds_per_demo"] = p.kept_seconds / std::max(1, p.demonstrations);
    result.details["teacher_total_seconds"] = p.total_seconds;
    result.details["teacher_demos_done"] =
        static_cast<double>(p.kept_done) / std::max(1, p.demonstrations);
    result.details["teacher_still_share"] =
        static_cast<double>(p.still_samples) / std::max(1, p.kept_samples);
    result.details["rollout_steps"] = rollout_steps;
  }
  return result;
}

}  // namespace

std::vector<ExperimentUnit> PlanUnits(const ExperimentConfig& config) {
  std::vector<ExperimentUnit> units;
  for (int run = 0; run < config.runs; ++run) {
    for (int demos : config.demos) {
      for (size_t c = 0; c < config.conditions.size(); ++c) {
        units.push_back({static_cast<int>(units.size()), demos, c, run});
      }
    }
  }
  return units;
}

UnitResult RunUnit(const ExperimentConfig& config, const ExperimentUnit& unit,
                   const std::atomic<bool>* cancel) {
  std::vector<uint64_t> test_seeds;
  for (int i = 0; i < config.tests; ++i) test_seeds.push_back(TestScenarioSeed(config.seed, i));
  UnitResult out;
  out.unit = unit;
  LossCurve curve;
  out.run = RunOne(config, unit, test_seeds, unit.run == 0 ? &curve : nullptr, cancel);
  if (unit.run == 0) out.curve = std::move(curve);
  return out;
}

ExperimentResult DescribeExperiment(const ExperimentConfig& config) {
  std::vector<uint64_t> test_seeds;
  for (int i = 0; i < config.tests; ++i) test_seeds.push_back(TestScenarioSeed(config.seed, i));
  const WorldMaker make_world = [&] {
    return worlds::MakeWorld(config.world, "none", 0.0, config.authors_compat, config.cell);
  };
  const std::unique_ptr<worlds::World> probe = make_world();
  ExperimentResult out;
  out.metric_name = probe->MetricName();
  out.higher_is_better = probe->HigherIsBetter();
  // When the expert drives (action scoring), success says nothing about the policy.
  out.has_success = probe->HasSuccess() && !probe->ScoresActions();
  out.metric_key = probe->MetricKey();
  out.step_seconds = probe->StepSeconds();
  out.episode_length = probe->EpisodeLength();
  out.play_per_scenario =
      config.play_per_scenario >= 0 ? config.play_per_scenario : probe->PlaySamplesPerScenario();
  const std::vector<ScenarioOutcome> expert = EvaluateExpert(make_world, test_seeds);
  out.expert_metric = Mean(Metrics(expert));
  out.expert_success_rate = SuccessRate(expert);
  return out;
}

ExperimentResult AssembleExperiment(const ExperimentConfig& config, ExperimentResult described,
                                    const std::vector<UnitResult>& units) {
  ExperimentResult out = std::move(described);
  // Report in (demos, condition, run) order regardless of which unit finished first.
  for (int demos : config.demos) {
    for (size_t c = 0; c < config.conditions.size(); ++c) {
      std::vector<const UnitResult*> runs;
      for (const UnitResult& u : units) {
        if (u.unit.demos == demos && u.unit.condition == c) {
          runs.push_back(&u);
        }
      }
      std::sort(runs.begin(), runs.end(),
                [](const UnitResult* a, const UnitResult* b) { return a->unit.run < b->unit.run; });
      LossCurve curve;
      for (const UnitResult* u : runs) {
        out.runs.push_back(u->run);
        out.runs.back().has_success = out.has_success;
        if (u->curve) curve = *u->curve;
      }
      out.loss_curves.push_back(std::move(curve));
    }
  }
  return out;
}

ExperimentResult RunExperiment(const ExperimentConfig& config, const RunObserver& on_run,
                               const std::atomic<bool>* cancel) {
  ValidateExperimentConfig(config);
  const auto start = std::chrono::steady_clock::now();
  ExperimentResult described = DescribeExperiment(config);
  const std::vector<ExperimentUnit> units = PlanUnits(config);
  std::vector<UnitResult> results(units.size());
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex mutex;
  auto worker = [&] {
    while (!failed) {
      const size_t i = next++;
      if (i >= units.size()) return;
      if (cancel != nullptr && *cancel) {
        failed = true;
        std::lock_guard<std::mutex> lock(mutex);
        if (!first_error) first_error = std::make_exception_ptr(UserError("cancelled"));
        return;
      }
      try {
        results[i] = RunUnit(config, units[i], cancel);
        results[i].run.has_success = described.has_success;
        std::lock_guard<std::mutex> lock(mutex);
        if (on_run) on_run(results[i].run);
      } catch (...) {
        failed = true;
        std::lock_guard<std::mutex> lock(mutex);
        if (!first_error) first_error = std::current_exception();
      }
    }
  };
  const int jobs = std::min<int>(config.jobs, static_cast<int>(units.size()));
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  if (first_error) std::rethrow_exception(first_error);

  ExperimentResult out = AssembleExperiment(config, std::move(described), results);
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace recon::experiments
