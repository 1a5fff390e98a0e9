#include "app/cli/session_training.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "app/cli/result_staleness.h"
#include "app/cli/session_world.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/parallel_for.h"
#include "engine/core/pauses.h"
#include "engine/core/rng.h"
#include "engine/core/stats.h"
#include "engine/experiments/evaluation.h"
#include "engine/experiments/recipe.h"
#include "engine/store/rollout_replay.h"
#include "engine/teach/slow_takes.h"
#include "engine/teach/teacher_mix.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

constexpr int kHistoryPoints = 200;  // loss curve points kept per training run

std::string Label(const std::string& method, bool play) {
  if (method == "baseline") return "Baseline";
  return play ? "RECON (Play)" : "RECON";
}

/// The mean squared error of the policy's mean action against the demonstrations' actions.
double ActionMse(const learn::Policy& policy, const Dataset& data) {
  std::vector<std::vector<float>> xs, ys, us;
  for (const Episode& e : data.demos) {
    for (const Sample& s : e.samples) {
      xs.push_back(s.x);
      ys.push_back(s.y);
      us.push_back(s.u);
    }
  }
  if (xs.empty()) return std::nan("");
  double sum = 0;
  size_t count = 0;
  constexpr size_t kChunk = 256;
  for (size_t begin = 0; begin < xs.size(); begin += kChunk) {
    const size_t end = std::min(xs.size(), begin + kChunk);
    const std::vector<std::vector<float>> actions = policy.ActBatch(
        {xs.begin() + begin, xs.begin() + end}, {ys.begin() + begin, ys.begin() + end});
    for (size_t i = begin; i < end; ++i) {
      for (size_t j = 0; j < us[i].size(); ++j) {
        const double d = actions[i - begin][j] - us[i][j];
        sum += d * d;
        ++count;
      }
    }
  }
  return sum / static_cast<double>(count);
}

}  // namespace

SessionTrainingOptions WithRecipeDefaults(const store::Session& session,
                                          SessionTrainingOptions options) {
  const store::SessionManifest& m = session.manifest();
  const experiments::WorldRecipe recipe =
      experiments::RecipeForWorld(m.world, m.y_encoding == "uint8");
  if (options.steps == 0) options.steps = recipe.train.steps;
  if (options.learning_rate == 0.0) options.learning_rate = recipe.train.learning_rate;
  return options;
}

namespace {

/// Per named episode, whether a person gave it (the keyboard, a gamepad, a real cell's teleop):
/// everything but the scripted teacher, whose commands that move nothing are deliberate waits.
std::vector<bool> TakenByAPerson(const store::Session& session,
                                 const std::vector<std::string>& names) {
  std::vector<bool> person;
  for (const std::string& name : names) {
    if (name.rfind("demo_", 0) != 0) continue;  // play chunks are not demonstrations
    person.push_back(teach::IsAPersonsTake(session.Find(name).meta.source));
  }
  return person;
}

}  // namespace

store::TrainingRecord TrainSessionMethod(
    const store::Session& session, const std::string& method, const SessionTrainingOptions& flags,
    const std::function<void(const TrainingProgress&)>& on_progress,
    const std::atomic<bool>* cancel) {
  const uint64_t seed = flags.seed;
  const store::SessionManifest& m = session.manifest();
  const bool recon = method == "recon";
  store::DatasetOptions options;
  options.split = store::Split::kTrain;
  options.include_bad = flags.include_bad;
  options.include_play = recon && !!flags.use_play;
  Dataset data = session.LoadDataset(options);
  const std::vector<std::string> trained_on = session.DatasetEpisodeNames(options);
  if (data.demos.empty()) {
    throw UserError("session " + session.dir() +
                    " has no demonstrations to train on (record some with `recon record`, or "
                    "check that not all are bad or in the validation split)");
  }
  const bool play = !data.play.empty();
  options.split = store::Split::kValid;
  options.include_play = false;
  Dataset valid = session.LoadDataset(options);

  // The recipe for a person's takes when most of the demonstrations trained on are a person's.
  const std::vector<bool> persons = TakenByAPerson(session, trained_on);
  experiments::WorldRecipe recipe = experiments::RecipeForWorld(
      m.world, m.y_encoding == "uint8", teach::MostlyAPersonsTakes(persons));
  // A person's pauses are left out where the recipe says so (pauses.h), from both splits.
  if (!flags.keep_pauses && !recipe.pause_motion.empty()) {
    data = WithoutPauses(data, recipe.pause_motion, nullptr, persons);
    options.split = store::Split::kValid;
    valid = WithoutPauses(valid, recipe.pause_motion, nullptr,
                          TakenByAPerson(session, session.DatasetEpisodeNames(options)));
  }
  learn::NetworkConfig network = recipe.network;
  network.feature_dim = flags.feature_dim;
  if (flags.action_chunk != 0) network.action_chunk = flags.action_chunk;
  learn::TrainConfig train = recipe.train;
  train.method = learn::ParseMethod(method);
  train.loss = learn::ParseLossKind(flags.loss);
  // 0 leaves the recipe's steps and rate (train starts from them), as WithRecipeDefaults does.
  if (flags.steps != 0) train.steps = flags.steps;
  train.batch_size = flags.batch;
  if (flags.learning_rate != 0.0) train.learning_rate = flags.learning_rate;
  train.seed = seed;
  learn::Trainer trainer(data, network, train);

  store::TrainingHistory history;
  const int window = std::max(1, train.steps / kHistoryPoints);
  store::TrainingLosses sums;
  int count = 0;
  TrainingProgress progress{method, Label(method, play), 0, train.steps, {}};
  trainer.SetObserver([&](const learn::StepMetrics& s) {
    if (s.step == 0) {  // a restart begins a fresh curve
      history.Clear();
      count = 0;
      sums = {};
    }
    sums.action_loss += s.action_loss;
    sums.beacon_loss += s.beacon_loss;
    sums.play_loss += s.play_loss;
    sums.total_loss += s.total_loss;
    sums.consistency_loss += s.consistency_loss;
    progress.step = s.step + 1;
    progress.curve_point = ++count == window;
    if (progress.curve_point) {
      history.Append(s.step + 1 - window / 2,
                     {sums.action_loss / count, sums.beacon_loss / count, sums.play_loss / count,
                      sums.consistency_loss / count, sums.total_loss / count});
      count = 0;
      sums = {};
      progress.latest = s;
      progress.latest.action_loss = static_cast<float>(history.action_loss.back());
      progress.latest.beacon_loss = static_cast<float>(history.beacon_loss.back());
      progress.latest.play_loss = static_cast<float>(history.play_loss.back());
      progress.latest.total_loss = static_cast<float>(history.total_loss.back());
    }
    if (on_progress) on_progress(progress);
  });
  const learn::TrainResult result = trainer.Train(cancel);
  if (result.cancelled) {
    throw TrainingCancelled("training " + Label(method, play) + " was cancelled at step " +
                                std::to_string(result.steps_run) + "; nothing was saved",
                            result.steps_run);
  }

  const std::string checkpoint = session.CheckpointPath(method);
  EnsureWritableDirectory(fs::path(checkpoint).parent_path().string());
  trainer.SaveCheckpoint(checkpoint);
  const learn::Policy policy = trainer.policy();
  store::TrainingRecord record;
  record.method = method;
  record.label = Label(method, play);
  record.checkpoint = store::Session::CheckpointRelativePath(method);
  record.steps = result.steps_run;
  record.attempts = result.attempts;
  record.seconds = result.seconds;
  record.seed = seed;
  record.loss = flags.loss;
  record.batch = flags.batch;
  record.learning_rate = train.learning_rate;
  record.feature_dim = flags.feature_dim;
  record.action_chunk = network.action_chunk;
  record.play_consistency = train.play_consistency;
  record.nll_min_std = train.nll_min_std;
  record.action_min_std = train.action_min_std;
  record.train_demos = static_cast<int>(data.demos.size());
  record.train_samples = data.NumDemoSamples();
  record.play_samples = static_cast<int>(data.play.size());
  record.valid_demos = static_cast<int>(valid.demos.size());
  // What the session's results are checked against later (result_staleness.h): which episodes
  // this model learnt from, chosen how, and which training this was.
  record.trained_on = store::TrainedOn{trained_on, options.include_bad, recon && !!flags.use_play};
  // The checkpoint's own digest: a record that outlives its model is found
  // (result_staleness.h).
  record.model_id = CheckpointModelId(checkpoint);
  const learn::StepMetrics& last = result.final_metrics;
  record.final_losses = {last.action_loss, last.beacon_loss, last.play_loss, last.consistency_loss,
                         last.total_loss};
  record.train_action_mse = ActionMse(policy, data);
  if (!valid.demos.empty()) record.valid_action_mse = ActionMse(policy, valid);
  record.history = std::move(history);
  const std::string path = session.TrainingRecordPath(method);
  EnsureWritableDirectory(fs::path(path).parent_path().string());
  store::WriteTrainingRecord(path, record);
  return record;
}

namespace {

/// The session's kept demonstrations (neither bad nor damaged), in order.
std::vector<teach::KeptTake> KeptTakes(const store::Session& session) {
  std::vector<teach::KeptTake> takes;
  for (const store::EpisodeEntry& e : session.demos()) {
    if (e.problem.empty() && !e.flags.bad) takes.push_back({e.name, e.meta.num_samples});
  }
  return takes;
}

}  // namespace

std::vector<int64_t> KeptDemoLengths(const store::Session& session) {
  std::vector<int64_t> lengths;
  for (const teach::KeptTake& take : KeptTakes(session)) lengths.push_back(take.samples);
  return lengths;
}

std::string SlowTakesWarningOf(const store::Session& session) {
  const double step_s = session.manifest().step_seconds;
  return teach::SlowTakesWarning(KeptTakes(session), step_s > 0 ? step_s : 1.0);
}

int SessionRolloutSteps(const store::Session& session, const worlds::World& world,
                        std::string* note) {
  // The kept demonstrations a model learns from: a slow teacher's policy is as slow.
  return experiments::RolloutSteps(world, KeptDemoLengths(session), experiments::kRolloutFactor,
                                   note);
}

store::RolloutSummary EvaluateSessionMethod(const store::Session& session,
                                            const std::string& method, int tests, uint64_t seed,
                                            bool keep_replay,
                                            const experiments::EvaluationHooks& hooks) {
  const store::SessionManifest& m = session.manifest();
  learn::ParseMethod(method);
  const std::string checkpoint = session.CheckpointPath(method);
  if (!fs::exists(checkpoint)) {
    throw UserError("no checkpoint " + checkpoint + ": run `recon train --session " +
                    session.dir() + " --methods " + method + "` first");
  }
  std::vector<uint64_t> seeds;
  for (int i = 0; i < tests; ++i) seeds.push_back(Rng::Derive(seed, i));
  const experiments::WorldMaker make_world = [&m] { return MakeSessionWorld(m, "none"); };
  const std::unique_ptr<worlds::World> probe = make_world();
  // Which model these rollouts are of (read before loading, so a training that replaces the
  // checkpoint meanwhile makes them out of date rather than mislabelled).
  const std::string model_id = CheckpointModelId(checkpoint);
  const learn::Policy policy = learn::LoadPolicy(checkpoint);
  const auto start = std::chrono::steady_clock::now();
  const int steps = SessionRolloutSteps(session, *probe);
  std::vector<experiments::ScenarioOutcome> outcomes =
      experiments::EvaluatePolicy(make_world, policy, seeds, keep_replay, hooks, nullptr, steps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<double> metrics = experiments::Metrics(outcomes);
  std::vector<double> successes;
  store::RolloutSummary summary;
  for (size_t i = 0; i < outcomes.size(); ++i) {
    successes.push_back(outcomes[i].succeeded ? 1.0 : 0.0);
    summary.per_scenario.push_back(
        {seeds[i], outcomes[i].metric, outcomes[i].succeeded, outcomes[i].details});
  }
  const std::optional<store::TrainingRecord> trained = store::ReadTrainingRecord(session, method);
  // The replay goes first: once the summary names it, it is there. A replay left from an earlier
  // evaluation would show other rollouts than the summary describes, so it goes when none is
  // kept.
  const std::string replay_path = session.RolloutReplayPath(method);
  const bool has_replay = !outcomes.empty() && !outcomes.front().replay.empty();
  EnsureWritableDirectory(fs::path(replay_path).parent_path().string());
  if (has_replay) {
    store::RolloutReplay replay;
    replay.world = probe->Name();
    replay.method = method;
    replay.state_size = static_cast<int>(outcomes.front().replay.front().size());
    for (size_t i = 0; i < outcomes.size(); ++i) {
      replay.scenarios.push_back(
          {seeds[i], outcomes[i].metric, outcomes[i].succeeded, std::move(outcomes[i].replay)});
    }
    store::WriteRolloutReplay(replay_path, replay);
    summary.replay = store::Session::RolloutReplayRelativePath(method);
  } else {
    std::error_code ignored;
    fs::remove(replay_path, ignored);
  }
  summary.method = method;
  summary.label = trained ? trained->label : method;
  summary.checkpoint = store::Session::CheckpointRelativePath(method);
  summary.model_id = model_id;
  summary.metric_name = probe->MetricName();
  summary.metric_key = probe->MetricKey();
  summary.higher_is_better = probe->HigherIsBetter();
  summary.metric_mean = Mean(metrics);
  summary.metric_sem = StandardError(metrics);
  summary.has_success = probe->HasSuccess();
  summary.success_rate = Mean(successes);
  summary.success_sem = StandardError(successes);
  summary.details = experiments::MeanDetails(outcomes);
  summary.tests = tests;
  summary.seed = seed;
  summary.seconds = seconds;
  store::WriteRolloutSummary(session.RolloutSummaryPath(method), summary);
  return summary;
}

std::vector<store::RolloutSummary> EvaluateSessionMethods(
    const store::Session& session, const std::vector<std::string>& methods, int tests,
    uint64_t seed, const std::function<void(const store::RolloutSummary&)>& on_done,
    const std::function<void(size_t method, int done, int steps)>& on_step,
    const std::atomic<bool>* cancel) {
  std::vector<store::RolloutSummary> summaries(methods.size());
  std::mutex done_mutex;
  RethrowFirst(ParallelForEachCatching(
      methods.size(), std::max(1u, std::thread::hardware_concurrency()), [&](size_t i) {
        experiments::EvaluationHooks hooks;
        hooks.cancel = cancel;
        if (on_step) hooks.on_step = [&, i](int done, int steps) { on_step(i, done, steps); };
        summaries[i] = EvaluateSessionMethod(session, methods[i], tests, seed, true, hooks);
        if (on_done) {
          std::lock_guard<std::mutex> lock(done_mutex);
          on_done(summaries[i]);
        }
      }));
  return summaries;
}

uint64_t DefaultTrainingSeed(const store::Session& session) {
  return Rng::Derive(session.manifest().seed, 7);
}

uint64_t DefaultTestSeed(const store::Session& session) {
  return Rng::Derive(session.manifest().seed, 11);
}

}  // namespace recon::cli
