#include "app/cli/train_commands.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/session_world.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/progress.h"
#include "engine/core/rng.h"
#include "engine/core/stats.h"
#include "engine/experiments/evaluation.h"
#include "engine/experiments/recipe.h"
#include "engine/learn/learner.h"
#include "engine/store/session.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kHistoryPoints = 200;  // loss curve points kept per training run

struct TrainFlags {
  std::string session;
  std::vector<std::string> methods = {"baseline", "recon"};
  int steps = 6001;
  int batch = 20;
  double learning_rate = 4e-4;
  int feature_dim = 6;
  uint64_t seed = 0;  ///< 0: the session's seed
  std::string loss = "nll";
  bool no_play = false;
  bool include_bad = false;
};

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

void TrainOne(const store::Session& session, const std::string& method, const TrainFlags& flags,
              uint64_t seed) {
  const store::SessionManifest& m = session.manifest();
  const bool recon = method == "recon";
  store::DatasetOptions options;
  options.split = store::Split::kTrain;
  options.include_bad = flags.include_bad;
  options.include_play = recon && !flags.no_play;
  const Dataset data = session.LoadDataset(options);
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
  train.steps = flags.steps;
  train.batch_size = flags.batch;
  train.learning_rate = flags.learning_rate;
  train.seed = seed;
  learn::Trainer trainer(data, network, train);

  json history = {{"step", json::array()},
                  {"action_loss", json::array()},
                  {"beacon_loss", json::array()},
                  {"play_loss", json::array()},
                  {"total_loss", json::array()}};
  const int window = std::max(1, train.steps / kHistoryPoints);
  double sums[4] = {0, 0, 0, 0};
  int count = 0;
  ProgressLine progress("training " + Label(method, play), train.steps);
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
    if (++count == window) {
      history["step"].push_back(s.step + 1 - window / 2);
      history["action_loss"].push_back(sums[0] / count);
      history["beacon_loss"].push_back(sums[1] / count);
      history["play_loss"].push_back(sums[2] / count);
      history["total_loss"].push_back(sums[3] / count);
      count = 0;
      for (double& v : sums) v = 0;
      progress.Advance(window);
    }
  });
  const learn::TrainResult result = trainer.Train();
  progress.Finish();

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
      {"learning_rate", flags.learning_rate},
      {"feature_dim", flags.feature_dim},
      {"train_demos", data.demos.size()},
      {"train_samples", data.NumDemoSamples()},
      {"play_samples", data.play.size()},
      {"valid_demos", valid.demos.size()},
      {"final",
       {{"action_loss", result.final_metrics.action_loss},
        {"beacon_loss", result.final_metrics.beacon_loss},
        {"play_loss", result.final_metrics.play_loss},
        {"total_loss", result.final_metrics.total_loss}}},
      {"train_action_mse", ActionMse(policy, data)},
      {"valid_action_mse", valid.demos.empty() ? json(nullptr) : json(ActionMse(policy, valid))},
      {"history", history}};
  const std::string path = (fs::path(session.dir()) / "training" / (method + ".json")).string();
  EnsureWritableDirectory(fs::path(path).parent_path().string());
  WriteFileAtomically(path, record.dump(1) + "\n");
  std::printf(
      "%-14s %zu demos (%lld samples), %zu play, %d steps in %.1f s, seed %llu: action "
      "MSE train %.4g%s; wrote %s\n",
      Label(method, play).c_str(), data.demos.size(), static_cast<long long>(data.NumDemoSamples()),
      data.play.size(), result.steps_run, result.seconds, static_cast<unsigned long long>(seed),
      record["train_action_mse"].get<double>(),
      valid.demos.empty()
          ? ""
          : (", valid " + std::to_string(record["valid_action_mse"].get<double>())).c_str(),
      checkpoint.c_str());
}

void RunTrain(const TrainFlags& flags, const GlobalOptions& global) {
  for (const std::string& method : flags.methods) learn::ParseMethod(method);
  // Read-write: training results go into the session (and the writer lock keeps a recording
  // from changing the data underneath).
  const store::Session session = store::Session::Open(flags.session);
  learn::SetThreads(global.threads);
  const uint64_t seed = flags.seed != 0 ? flags.seed : Rng::Derive(session.manifest().seed, 7);
  std::printf(
      "recon train: session %s (%s), methods %s, training seed %llu\n", flags.session.c_str(),
      session.manifest().world.c_str(),
      [&] {
        std::string names;
        for (const std::string& m : flags.methods) names += (names.empty() ? "" : ",") + m;
        return names;
      }()
          .c_str(),
      static_cast<unsigned long long>(seed));
  std::fflush(stdout);
  for (const std::string& method : flags.methods) TrainOne(session, method, flags, seed);
}

struct EvalFlags {
  std::string session;
  std::vector<std::string> methods;  ///< empty: every trained checkpoint
  int tests = 20;
  uint64_t seed = 0;
};

void RunEval(const EvalFlags& flags) {
  const store::Session session = store::Session::Open(flags.session);
  const store::SessionManifest& m = session.manifest();
  std::vector<std::string> methods = flags.methods;
  if (methods.empty()) {
    for (const char* method : {"baseline", "recon"}) {
      if (fs::exists(fs::path(flags.session) / "checkpoints" / (std::string(method) + ".ckpt"))) {
        methods.push_back(method);
      }
    }
    if (methods.empty()) {
      throw UserError("session " + flags.session +
                      " has no trained policy: run `recon train --session " + flags.session +
                      "` first");
    }
  }
  // Test scenarios come from their own seed stream: never the scenarios taught.
  const uint64_t seed = flags.seed != 0 ? flags.seed : Rng::Derive(m.seed, 11);
  std::vector<uint64_t> seeds;
  for (int i = 0; i < flags.tests; ++i) seeds.push_back(Rng::Derive(seed, i));
  MakeSessionWorld(m, "none");  // fails early for sessions without a simulated world
  const experiments::WorldMaker make_world = [&m] { return MakeSessionWorld(m, "none"); };
  std::printf(
      "recon eval: %zu method(s) on %d test scenarios of %s with the beacons removed "
      "(seeds derived from %llu)\n",
      methods.size(), flags.tests, m.world.c_str(), static_cast<unsigned long long>(seed));
  std::fflush(stdout);
  const std::unique_ptr<worlds::World> probe = make_world();
  ProgressLine progress("rolling out", static_cast<int64_t>(methods.size()));
  for (const std::string& method : methods) {
    learn::ParseMethod(method);
    const std::string checkpoint =
        (fs::path(flags.session) / "checkpoints" / (method + ".ckpt")).string();
    if (!fs::exists(checkpoint)) {
      throw UserError("no checkpoint " + checkpoint + ": run `recon train --session " +
                      flags.session + " --methods " + method + "` first");
    }
    const learn::Policy policy = learn::LoadPolicy(checkpoint);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<experiments::ScenarioOutcome> outcomes =
        experiments::EvaluatePolicy(make_world, policy, seeds);
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
    const std::optional<json> trained = [&]() -> std::optional<json> {
      std::ifstream in(fs::path(flags.session) / "training" / (method + ".json"));
      if (!in) return std::nullopt;
      return json::parse(in, nullptr, false);
    }();
    const std::string label = trained && trained->is_object() && trained->contains("label")
                                  ? (*trained)["label"].get<std::string>()
                                  : method;
    const json record = {{"method", method},
                         {"label", label},
                         {"checkpoint", fs::path("checkpoints") / (method + ".ckpt")},
                         {"metric_name", probe->MetricName()},
                         {"metric_key", probe->MetricKey()},
                         {"higher_is_better", probe->HigherIsBetter()},
                         {"metric_mean", Mean(metrics)},
                         {"metric_sem", StandardError(metrics)},
                         {"has_success", probe->HasSuccess()},
                         {"success_rate", Mean(successes)},
                         {"success_sem", StandardError(successes)},
                         {"details", experiments::MeanDetails(outcomes)},
                         {"tests", flags.tests},
                         {"seed", seed},
                         {"seconds", seconds},
                         {"per_scenario", per_scenario}};
    const std::string path = (fs::path(flags.session) / "rollouts" / (method + ".json")).string();
    EnsureWritableDirectory(fs::path(path).parent_path().string());
    WriteFileAtomically(path, record.dump(1) + "\n");
    progress.Advance(1, label);
    std::printf("\n%-14s %s %.4g ± %.2g%s  (%.1f s; wrote %s)\n", label.c_str(),
                probe->MetricKey().c_str(), Mean(metrics), StandardError(metrics),
                probe->HasSuccess()
                    ? ("  success " +
                       std::to_string(static_cast<int>(std::lround(100 * Mean(successes)))) + "%")
                          .c_str()
                    : "",
                seconds, path.c_str());
  }
  progress.Finish();
}

}  // namespace

void AddTrainCommands(CLI::App& app, const GlobalOptions& global) {
  auto flags = std::make_shared<TrainFlags>();
  CLI::App* train = app.add_subcommand("train", "train RECON and the Baseline on a session");
  train->add_option("--session", flags->session, "session folder")->required();
  train->add_option("--methods,--method", flags->methods, "recon, baseline, or both")
      ->delimiter(',')
      ->capture_default_str();
  train->add_option("--steps", flags->steps, "training steps")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  train->add_option("--batch", flags->batch, "batch size")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  train->add_option("--lr", flags->learning_rate, "Adam learning rate")->capture_default_str();
  train->add_option("--feature-dim", flags->feature_dim, "feature size k (must exceed d)")
      ->capture_default_str();
  train->add_option("--loss", flags->loss, "nll (paper) or mse-sample (authors' code)")
      ->capture_default_str();
  train->add_option("--seed", flags->seed, "training seed (default: derived from the session's)");
  train->add_flag("--no-play", flags->no_play, "train RECON without the session's play data");
  train->add_flag("--include-bad", flags->include_bad, "also train on demonstrations marked bad");
  train->callback([flags, &global] { RunTrain(*flags, global); });

  auto eval_flags = std::make_shared<EvalFlags>();
  CLI::App* eval = app.add_subcommand(
      "eval", "roll the trained policies out in the simulated cell, beacons removed");
  eval->add_option("--session", eval_flags->session, "session folder")->required();
  eval->add_option("--methods,--method", eval_flags->methods,
                   "which checkpoints (default: every trained one)")
      ->delimiter(',');
  eval->add_option("--tests", eval_flags->tests, "test scenarios")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  eval->add_option("--seed", eval_flags->seed, "test scenario seed (default: from the session's)");
  eval->callback([eval_flags] { RunEval(*eval_flags); });
}

}  // namespace recon::cli
