#include "app/cli/session_training.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "app/cli/result_staleness.h"
#include "app/cli/session_summary.h"
#include "app/cli/session_world.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/rng.h"
#include "engine/core/stats.h"
#include "engine/experiments/evaluation.h"
#include "engine/experiments/recipe.h"
#include "engine/store/rollout_replay.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

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

json TrainSessionMethod(const store::Session& session, const std::string& method,
                        const SessionTrainingOptions& flags,
                        const std::function<void(const TrainingProgress&)>& on_progress,
                        const std::atomic<bool>* cancel) {
  const uint64_t seed = flags.seed;
  const store::SessionManifest& m = session.manifest();
  const bool recon = method == "recon";
  store::DatasetOptions options;
  options.split = store::Split::kTrain;
  options.include_bad = flags.include_bad;
  options.include_play = recon && !!flags.use_play;
  const Dataset data = session.LoadDataset(options);
  const std::vector<std::string> trained_on = session.DatasetEpisodeNames(options);
  if (data.demos.empty()) {
    throw UserError("session " + session.dir() +
                    " has no demonstrations to train on (record some with `recon record`, or "
                    "check that not all are bad or in the validation split)");
  }
  const bool play = !data.play.empty();
  options.split = store::Split::kValid;
  options.include_play = false;
  const Dataset valid = session.LoadDataset(options);

  experiments::WorldRecipe recipe = experiments::RecipeForWorld(m.world, m.y_encoding == "uint8");
  learn::NetworkConfig network = recipe.network;
  network.feature_dim = flags.feature_dim;
  learn::TrainConfig train = recipe.train;
  train.method = learn::ParseMethod(method);
  train.loss = learn::ParseLossKind(flags.loss);
  // 0 leaves the recipe's steps and rate (train starts from them), as WithRecipeDefaults does.
  if (flags.steps != 0) train.steps = flags.steps;
  train.batch_size = flags.batch;
  if (flags.learning_rate != 0.0) train.learning_rate = flags.learning_rate;
  train.seed = seed;
  learn::Trainer trainer(data, network, train);

  json history = {{"step", json::array()},
                  {"action_loss", json::array()},
                  {"beacon_loss", json::array()},
                  {"play_loss", json::array()},
                  {"consistency_loss", json::array()},
                  {"total_loss", json::array()}};
  const int window = std::max(1, train.steps / kHistoryPoints);
  double sums[5] = {0, 0, 0, 0, 0};
  int count = 0;
  TrainingProgress progress{method, Label(method, play), 0, train.steps, {}};
  trainer.SetObserver([&](const learn::StepMetrics& s) {
    if (s.step == 0) {  // a restart begins a fresh curve
      for (auto& [key, values] : history.items()) values = json::array();
      count = 0;
      for (double& v : sums) v = 0;
    }
    sums[0] += s.action_loss;
    sums[1] += s.beacon_loss;
    sums[2] += s.play_loss;
    sums[3] += s.total_loss;
    sums[4] += s.consistency_loss;
    if (++count == window) {
      history["step"].push_back(s.step + 1 - window / 2);
      history["action_loss"].push_back(sums[0] / count);
      history["beacon_loss"].push_back(sums[1] / count);
      history["play_loss"].push_back(sums[2] / count);
      history["total_loss"].push_back(sums[3] / count);
      history["consistency_loss"].push_back(sums[4] / count);
      count = 0;
      for (double& v : sums) v = 0;
      progress.step = s.step + 1;
      progress.latest = s;
      progress.latest.action_loss = static_cast<float>(history["action_loss"].back().get<double>());
      progress.latest.beacon_loss = static_cast<float>(history["beacon_loss"].back().get<double>());
      progress.latest.play_loss = static_cast<float>(history["play_loss"].back().get<double>());
      progress.latest.total_loss = static_cast<float>(history["total_loss"].back().get<double>());
      if (on_progress) on_progress(progress);
    }
  });
  const learn::TrainResult result = trainer.Train(cancel);
  if (result.cancelled) {
    throw UserError("training " + Label(method, play) + " was cancelled at step " +
                    std::to_string(result.steps_run) + "; nothing was saved");
  }

  const std::string checkpoint =
      (fs::path(session.dir()) / "checkpoints" / (method + ".ckpt")).string();
  EnsureWritableDirectory(fs::path(checkpoint).parent_path().string());
  trainer.SaveCheckpoint(checkpoint);
  const learn::Policy policy = trainer.policy();
  const json record = {
      {"method", method},
      {"label", Label(method, play)},
      {"checkpoint", fs::path("checkpoints") / (method + ".ckpt")},
      {"steps", result.steps_run},
      {"attempts", result.attempts},
      {"seconds", result.seconds},
      {"seed", seed},
      {"loss", flags.loss},
      {"batch", flags.batch},
      {"learning_rate", train.learning_rate},
      {"feature_dim", flags.feature_dim},
      {"play_consistency", train.play_consistency},
      {"nll_min_std", train.nll_min_std},
      {"action_min_std", train.action_min_std},
      {"train_demos", data.demos.size()},
      {"train_samples", data.NumDemoSamples()},
      {"play_samples", data.play.size()},
      {"valid_demos", valid.demos.size()},
      // What the session's results are checked against later (result_staleness.h): which
      // episodes this model learnt from, chosen how, and which training this was.
      {"trained_on",
       {{"episodes", trained_on},
        {"include_bad", options.include_bad},
        {"use_play", recon && !!flags.use_play}}},
      // The checkpoint's own digest: a record that outlives its model is found
      // (result_staleness.h).
      {"model_id", CheckpointModelId(checkpoint)},
      {"final",
       {{"action_loss", result.final_metrics.action_loss},
        {"beacon_loss", result.final_metrics.beacon_loss},
        {"play_loss", result.final_metrics.play_loss},
        {"consistency_loss", result.final_metrics.consistency_loss},
        {"total_loss", result.final_metrics.total_loss}}},
      {"train_action_mse", ActionMse(policy, data)},
      {"valid_action_mse", valid.demos.empty() ? json(nullptr) : json(ActionMse(policy, valid))},
      {"history", history}};
  const std::string path = (fs::path(session.dir()) / "training" / (method + ".json")).string();
  EnsureWritableDirectory(fs::path(path).parent_path().string());
  WriteFileAtomically(path, record.dump(1) + "\n");
  return record;
}

json EvaluateSessionMethod(const store::Session& session, const std::string& method, int tests,
                           uint64_t seed, bool keep_replay) {
  const store::SessionManifest& m = session.manifest();
  learn::ParseMethod(method);
  const std::string checkpoint =
      (fs::path(session.dir()) / "checkpoints" / (method + ".ckpt")).string();
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
  std::vector<experiments::ScenarioOutcome> outcomes =
      experiments::EvaluatePolicy(make_world, policy, seeds, keep_replay);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<double> metrics = experiments::Metrics(outcomes);
  std::vector<double> successes;
  json per_scenario = json::array();
  for (size_t i = 0; i < outcomes.size(); ++i) {
    successes.push_back(outcomes[i].succeeded ? 1.0 : 0.0);
    per_scenario.push_back({{"seed", seeds[i]},
                            {"metric", outcomes[i].metric},
                            {"succeeded", outcomes[i].succeeded},
                            {"details", outcomes[i].details}});
  }
  const std::optional<json> trained =
      ReadJsonFile((fs::path(session.dir()) / "training" / (method + ".json")).string());
  const std::string label = trained && trained->is_object() && trained->contains("label")
                                ? (*trained)["label"].get<std::string>()
                                : method;
  // The replay goes first: once the JSON names it, it is there. A replay left from an earlier
  // evaluation would show other rollouts than the JSON describes, so it goes when none is kept.
  const fs::path replay_name = fs::path("rollouts") / (method + ".replay.h5");
  const std::string replay_path = (fs::path(session.dir()) / replay_name).string();
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
  } else {
    std::error_code ignored;
    fs::remove(replay_path, ignored);
  }
  json record = {{"method", method},
                 {"label", label},
                 {"checkpoint", fs::path("checkpoints") / (method + ".ckpt")},
                 {"model_id", model_id},
                 {"metric_name", probe->MetricName()},
                 {"metric_key", probe->MetricKey()},
                 {"higher_is_better", probe->HigherIsBetter()},
                 {"metric_mean", Mean(metrics)},
                 {"metric_sem", StandardError(metrics)},
                 {"has_success", probe->HasSuccess()},
                 {"success_rate", Mean(successes)},
                 {"success_sem", StandardError(successes)},
                 {"details", experiments::MeanDetails(outcomes)},
                 {"tests", tests},
                 {"seed", seed},
                 {"seconds", seconds},
                 {"per_scenario", per_scenario}};
  if (has_replay) record["replay"] = replay_name.string();
  const std::string path = (fs::path(session.dir()) / "rollouts" / (method + ".json")).string();
  WriteFileAtomically(path, record.dump(1) + "\n");
  return record;
}

uint64_t DefaultTrainingSeed(const store::Session& session) {
  return Rng::Derive(session.manifest().seed, 7);
}

uint64_t DefaultTestSeed(const store::Session& session) {
  return Rng::Derive(session.manifest().seed, 11);
}

}  // namespace recon::cli
