#include "app/cli/train_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/option_checks.h"
#include "app/cli/session_probe.h"
#include "app/cli/session_saliency.h"
#include "app/cli/session_training.h"
#include "app/cli/session_world.h"
#include "engine/core/error.h"
#include "engine/core/parallel_for.h"
#include "engine/core/progress.h"
#include "engine/learn/learner.h"
#include "engine/store/session.h"

namespace recon::cli {

namespace {

struct TrainFlags {
  std::string session;
  std::vector<std::string> methods = {"baseline", "recon"};
  int steps = 0;  ///< 0: the world's recipe
  int batch = 20;
  double learning_rate = 0.0;  ///< 0: the world's recipe
  int feature_dim = 6;
  uint64_t seed = 0;  ///< 0: derived from the session's
  std::string loss = "nll";
  bool no_play = false;
  bool include_bad = false;
  bool keep_pauses = false;
  int action_chunk = 0;  ///< 0: the recipe's
};

void RunTrain(const TrainFlags& flags, const GlobalOptions& global) {
  for (size_t i = 0; i < flags.methods.size(); ++i) {
    learn::ParseMethod(flags.methods[i]);
    // Methods train at once, each into its own checkpoint: one named twice would write one file
    // from two threads.
    if (std::find(flags.methods.begin(), flags.methods.begin() + i, flags.methods[i]) !=
        flags.methods.begin() + i) {
      throw UserError("--methods: " + flags.methods[i] + " is named twice");
    }
  }
  // Read-write: training results go into the session (and the writer lock keeps a recording
  // from changing the data underneath).
  const store::Session session = store::Session::Open(flags.session);
  learn::SetThreads(global.threads);
  SessionTrainingOptions options;
  options.steps = flags.steps;
  options.batch = flags.batch;
  options.learning_rate = flags.learning_rate;
  options.feature_dim = flags.feature_dim;
  options.seed = flags.seed != 0 ? flags.seed : DefaultTrainingSeed(session);
  options.loss = flags.loss;
  options.use_play = !flags.no_play;
  options.include_bad = flags.include_bad;
  options.keep_pauses = flags.keep_pauses;
  options.action_chunk = flags.action_chunk;
  // Every episode any method will read is read once before the first checkpoint is replaced: a
  // damaged play chunk must not surface after the Baseline's checkpoint was already rewritten.
  {
    store::DatasetOptions everything;
    everything.split = store::Split::kAll;
    everything.include_bad = flags.include_bad;
    everything.include_play =
        options.use_play &&
        std::find(flags.methods.begin(), flags.methods.end(), "recon") != flags.methods.end();
    session.LoadDataset(everything);
  }
  std::string names;
  for (const std::string& m : flags.methods) names += (names.empty() ? "" : ",") + m;
  std::printf("recon train: session %s (%s), methods %s, training seed %llu\n",
              flags.session.c_str(), session.manifest().world.c_str(), names.c_str(),
              static_cast<unsigned long long>(options.seed));
  if (const std::string slow = SlowTakesWarningOf(session); !slow.empty()) {
    std::printf("note: %s\n", slow.c_str());
  }
  std::fflush(stdout);
  // Each trainer runs on one core (learner.h) and its result does not depend on what else runs,
  // so the methods train side by side, as in the studio: on 2 cores both take the slower one's
  // time. One bar counts the steps of all of them.
  const int steps = WithRecipeDefaults(session, options).steps;
  ProgressLine progress("training " + names,
                        static_cast<int64_t>(steps) * static_cast<int64_t>(flags.methods.size()));
  std::vector<int> done(flags.methods.size(), 0);
  std::vector<std::string> labels(flags.methods.size());
  std::mutex progress_mutex;
  const auto report = [&](size_t i, const TrainingProgress& p) {
    std::lock_guard<std::mutex> lock(progress_mutex);
    labels[i] = p.label;
    // A restart (the authors' rule) starts again at step 0; the bar holds until it passes
    // where it was.
    const int advance = std::max(0, p.step - done[i]);
    done[i] += advance;
    std::string detail;
    for (size_t j = 0; j < done.size(); ++j) {
      if (!labels[j].empty()) {
        detail += (detail.empty() ? "" : ", ") + labels[j] + " " + std::to_string(done[j]);
      }
    }
    progress.Advance(advance, detail);
  };
  std::vector<store::TrainingRecord> records(flags.methods.size());
  const std::vector<std::exception_ptr> errors = ParallelForEachCatching(
      flags.methods.size(), std::max(1u, std::thread::hardware_concurrency()), [&](size_t i) {
        records[i] = TrainSessionMethod(session, flags.methods[i], options,
                                        [&, i](const TrainingProgress& p) { report(i, p); });
      });
  progress.Finish();
  // A method that finished keeps its checkpoint and says so; then the first failure is reported.
  for (size_t i = 0; i < flags.methods.size(); ++i) {
    if (errors[i]) continue;
    const store::TrainingRecord& record = records[i];
    const std::string valid =
        record.valid_action_mse ? ", valid " + std::to_string(*record.valid_action_mse) : "";
    std::printf(
        "%-14s %d demos (%lld samples), %d play, %d steps in %.1f s, seed %llu: action MSE "
        "train %.4g%s; wrote %s/%s\n",
        record.label.c_str(), record.train_demos, static_cast<long long>(record.train_samples),
        record.play_samples, record.steps, record.seconds,
        static_cast<unsigned long long>(options.seed), record.train_action_mse, valid.c_str(),
        flags.session.c_str(), record.checkpoint.c_str());
  }
  std::fflush(stdout);
  try {
    RethrowFirst(errors);
  } catch (const DivergenceError& e) {
    // The learning rate is the user's to lower: say with which option.
    throw UserError(std::string(e.what()) + " with --lr");
  }
}

struct EvalFlags {
  std::string session;
  std::vector<std::string> methods;  ///< empty: every trained checkpoint
  int tests = 20;
  uint64_t seed = 0;
  // --probe: what the methods look at, instead of rollouts.
  bool probe = false;
  std::vector<std::string> objects;
  int grid = 10;
  int readout_scenes = 60;
  bool outcome = false;
  bool json = false;
  /// The options given that only moving objects in the simulated cell can use.
  std::vector<std::string> simulated_only;
  // --saliency demo_N: which pixels drive the actions over a recorded demonstration.
  std::string saliency;
  bool occlusion = false;
  int frames = 8;
};

void RunSaliency(const EvalFlags& flags) {
  const store::Session session = store::Session::Open(flags.session);
  SaliencySheetOptions options;
  options.episode = flags.saliency;
  options.methods = flags.methods;
  options.occlusion = flags.occlusion;
  options.frames = flags.frames;
  const SaliencySheet sheet = WriteSaliencySheet(session, options);
  std::string steps;
  for (int step : sheet.steps) steps += (steps.empty() ? "" : ", ") + std::to_string(step);
  std::string rows;
  for (const std::string& row : sheet.rows) rows += (rows.empty() ? "" : "; ") + row;
  std::printf("wrote %s: %s saliency over %s, rows: %s; columns: steps %s\n", sheet.path.c_str(),
              flags.occlusion ? "occlusion" : "input-gradient", flags.saliency.c_str(),
              rows.c_str(), steps.c_str());
}

void RunProbe(const EvalFlags& flags) {
  const store::Session session = store::Session::Open(flags.session);
  if (session.manifest().cell != "simulated" && !flags.simulated_only.empty()) {
    std::string given;
    for (const std::string& option : flags.simulated_only)
      given += (given.empty() ? "" : ", ") + option;
    throw UserError(given + ": " + session.dir() + " was taught on a " + session.manifest().cell +
                    " cell, which RECON Studio cannot simulate, so nothing can be moved or rolled "
                    "out; without " +
                    given +
                    " its methods are read out on its recorded frames; "
                    "nothing was written");
  }
  SessionProbeOptions options;
  options.methods = flags.methods;
  options.objects = flags.objects;
  options.grid.nx = options.grid.ny = flags.grid;
  options.readout_scenes = flags.readout_scenes;
  options.outcome = flags.outcome;
  std::unique_ptr<ProgressLine> progress;
  std::string phase;
  int shown = 0;  // units the line shows done: reports may come a batch of places at a time
  const store::ProbeSummary summary =
      ProbeSession(session, options, [&](const std::string& what, int done, int total) {
        if (what != phase) {
          if (progress) progress->Finish();
          progress = std::make_unique<ProgressLine>(what, total);
          phase = what;
          shown = 0;
        }
        if (done > shown) progress->Advance(done - shown);
        shown = std::max(shown, done);
      });
  if (progress) progress->Finish();
  if (flags.json) {
    std::printf("%s\n", store::ProbeSummaryToJson(summary).dump(2).c_str());
  } else {
    std::printf("%s", ProbeSummaryText(summary).c_str());
    std::printf(summary.readout_scenes > 0 ? "wrote %s and the heat maps beside it (%.1f s)\n"
                                           : "wrote %s (%.1f s)\n",
                session.ProbeSummaryPath().c_str(), summary.seconds);
  }
}

void RunEval(const EvalFlags& flags) {
  if (flags.probe) {
    RunProbe(flags);
    return;
  }
  if (!flags.saliency.empty()) {
    RunSaliency(flags);
    return;
  }
  const store::Session session = store::Session::Open(flags.session);
  const store::SessionManifest& m = session.manifest();
  const std::vector<std::string> methods = TrainedMethods(session, flags.methods, "to roll out");
  MakeSessionWorld(m, "none");  // fails early for sessions without a simulated world
  // Every checkpoint is loaded (and so checked) before the first rollout file is replaced.
  for (const std::string& method : methods) learn::LoadPolicy(session.CheckpointPath(method));
  // Test scenarios come from their own seed stream: never the scenarios taught.
  const uint64_t seed = flags.seed != 0 ? flags.seed : DefaultTestSeed(session);
  std::printf(
      "recon eval: %zu method(s) on %d test scenarios of %s with the beacons removed "
      "(seeds derived from %llu)\n",
      methods.size(), flags.tests, m.world.c_str(), static_cast<unsigned long long>(seed));
  std::fflush(stdout);
  // The methods roll out side by side, one core each (as they train); each line is printed in
  // the order of --methods once all are done.
  ProgressLine progress("rolling out", static_cast<int64_t>(methods.size()));
  const std::vector<store::RolloutSummary> summaries =
      EvaluateSessionMethods(session, methods, flags.tests, seed,
                             [&](const store::RolloutSummary& r) { progress.Advance(1, r.label); });
  progress.Finish();
  for (size_t i = 0; i < methods.size(); ++i) {
    const std::string& method = methods[i];
    const store::RolloutSummary& r = summaries[i];
    const std::string success =
        r.has_success
            ? "  success " + std::to_string(static_cast<int>(std::lround(100 * r.success_rate))) +
                  "%"
            : "";
    std::printf("%-14s %s %.4g ± %.2g%s  (%.1f s; wrote %s/%s)\n", r.label.c_str(),
                r.metric_key.c_str(), r.metric_mean, r.metric_sem, success.c_str(), r.seconds,
                flags.session.c_str(), store::Session::RolloutSummaryRelativePath(method).c_str());
  }
}

}  // namespace

void AddTrainCommands(CLI::App& app, const GlobalOptions& global) {
  auto flags = std::make_shared<TrainFlags>();
  CLI::App* train = app.add_subcommand("train", "train RECON and the Baseline on a session");
  train->add_option("--session", flags->session, "session folder")->required();
  train->add_option("--methods,--method", flags->methods, "recon, baseline, or both")
      ->delimiter(',')
      ->capture_default_str();
  train
      ->add_option("--steps", flags->steps,
                   "training steps (default: the world's recipe: 7500 on the tabletop, 15000 on "
                   "tabletop-state, 6001 elsewhere)")
      ->check(WholeBetween(1, kMaxSteps));
  train->add_option("--batch", flags->batch, "batch size")
      ->check(WholeBetween(1, kMaxBatch))
      ->capture_default_str();
  train
      ->add_option("--lr", flags->learning_rate,
                   "Adam learning rate (default: the world's recipe: 0.001 on the tabletop, "
                   "0.0004 elsewhere)")
      ->check(NumberBetween(learn::kMinLearningRate, kMaxLearningRate));
  train->add_option("--feature-dim", flags->feature_dim, "feature size k (must exceed d)")
      ->check(WholeBetween(1, kMaxFeatureDim))
      ->capture_default_str();
  train->add_option("--loss", flags->loss, "nll (paper) or mse-sample (authors' code)")
      ->capture_default_str();
  train->add_option("--seed", flags->seed, "training seed (default: derived from the session's)")
      ->check(SeedNumber());
  train->add_flag("--no-play", flags->no_play, "train RECON without the session's play data");
  train->add_flag("--include-bad", flags->include_bad, "also train on demonstrations marked bad");
  train->add_flag("--keep-pauses", flags->keep_pauses,
                  "also train on a person's pauses (commands that move nothing and change "
                  "nothing), which the tabletop's recipe leaves out");
  train
      ->add_option("--action-chunk", flags->action_chunk,
                   "actions predicted at once and ensembled over steps (ACT; 1 = off; default: "
                   "the recipe's: 20 for a person's takes on the tabletop, 10 otherwise)")
      ->check(WholeBetween(1, 100));
  train->callback([flags, &global] { RunTrain(*flags, global); });

  auto eval_flags = std::make_shared<EvalFlags>();
  CLI::App* eval = app.add_subcommand(
      "eval", "roll the trained policies out in the simulated cell, beacons removed");
  eval->add_option("--session", eval_flags->session, "session folder")->required();
  eval->add_option("--methods,--method", eval_flags->methods,
                   "which checkpoints (default: every trained one)")
      ->delimiter(',');
  eval->add_option("--tests", eval_flags->tests, "test scenarios")
      ->check(WholeBetween(1, kMaxTests))
      ->capture_default_str();
  CLI::Option* tests = eval->get_option("--tests");
  CLI::Option* seed = eval->add_option("--seed", eval_flags->seed,
                                       "test scenario seed (default: from the session's)")
                          ->check(SeedNumber());
  CLI::Option* probe = eval->add_flag(
      "--probe", eval_flags->probe,
      "instead of rolling out: move each object over a grid of table places in a test scene and "
      "measure how much each method's action and features change (what it looks at), and read "
      "each object's position out of the features on other test scenes (a real cell's session: "
      "read out on its recorded frames against the beacons' readings, nothing moved)");
  probe->excludes(tests)->excludes(seed);
  eval->add_option("--object", eval_flags->objects,
                   "with --probe: the object to move (repeatable; default: every one)")
      ->needs(probe);
  eval->add_option("--grid", eval_flags->grid, "with --probe: grid places per side")
      ->check(WholeBetween(2, 100))
      ->capture_default_str()
      ->needs(probe);
  eval->add_option("--readout-scenes", eval_flags->readout_scenes,
                   "with --probe: test scenes for the features' read-out")
      ->check(WholeBetween(8, 2000))
      ->capture_default_str()
      ->needs(probe);
  eval->add_flag("--outcome", eval_flags->outcome,
                 "with --probe: also roll each method out whole from every place (does it still "
                 "do the task with the object there? slower by the episode's length)")
      ->needs(probe);
  eval->add_flag("--json", eval_flags->json, "with --probe: print the numbers as one JSON object")
      ->needs(probe);
  CLI::Option* saliency = eval->add_option(
      "--saliency", eval_flags->saliency,
      "instead of rolling out: draw which pixels drive each method's action over "
      "the recorded demonstration EPISODE (demo_N) into the session's probe/ folder");
  saliency->excludes(tests)->excludes(seed)->excludes(probe);
  eval->add_flag("--occlusion", eval_flags->occlusion,
                 "with --saliency: an occlusion map instead of the input gradient")
      ->needs(saliency);
  eval->add_option("--frames", eval_flags->frames, "with --saliency: frames across the sheet")
      ->check(WholeBetween(1, 64))
      ->capture_default_str()
      ->needs(saliency);
  eval->callback([eval_flags, eval] {
    eval_flags->simulated_only.clear();
    for (const char* option : {"--object", "--grid", "--readout-scenes", "--outcome"}) {
      if (eval->count(option) > 0) eval_flags->simulated_only.push_back(option);
    }
    RunEval(*eval_flags);
  });
}

}  // namespace recon::cli
