#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "engine/core/error.h"
#include "engine/experiments/evaluation.h"
#include "engine/learn/learner.h"
#include "engine/store/rollout_summary.h"
#include "engine/store/session.h"
#include "engine/store/training_record.h"

namespace recon::cli {

/// How `recon train` and the studio train a method on a session (the world's recipe otherwise).
struct SessionTrainingOptions {
  int steps = 0;  ///< 0: the world's recipe (WithRecipeDefaults)
  int batch = 20;
  double learning_rate = 0.0;  ///< 0: the world's recipe (WithRecipeDefaults)
  int feature_dim = 6;
  uint64_t seed = 0;
  std::string loss = "nll";
  bool use_play = true;  ///< RECON trains its beacon net on the session's play data too
  bool include_bad = false;
  /// Train on a person's pauses too; by default the world's recipe leaves them out
  /// (WorldRecipe::pause_motion).
  bool keep_pauses = false;
  /// Actions predicted at once (ACT); 0: the recipe's (chunks of 20 for a person's takes on the
  /// tabletop, 10 for the scripted teacher's).
  int action_chunk = 0;
};

/// Where a training run is, reported every few steps.
struct TrainingProgress {
  std::string method;  ///< "baseline" or "recon"
  std::string label;   ///< "Baseline", "RECON (Play)"
  int step = 0;
  int steps = 0;
  /// Reported after every step, so a progress bar moves however long the run; the losses are
  /// a new point of the loss curve only where `curve_point` holds (one per window of steps).
  bool curve_point = false;
  learn::StepMetrics latest;  ///< losses averaged over the last window
};

/// `options` with the steps and learning rate it leaves at 0 taken from the session's world's
/// recipe (experiments/recipe.h), so that a session trains as the experiments do.
SessionTrainingOptions WithRecipeDefaults(const store::Session& session,
                                          SessionTrainingOptions options);

/// A training stopped because it was asked to: nothing of it was saved. `step` is where it
/// stopped.
class TrainingCancelled : public UserError {
 public:
  TrainingCancelled(const std::string& message, int step) : UserError(message), step_(step) {}
  int step() const { return step_; }

 private:
  int step_;
};

/// Trains `method` ("baseline" or "recon") on the session's training split, then writes its
/// checkpoint and its training record (recipe, seed, final losses, train and validation action
/// MSE, loss curve) and returns that record. `on_progress` is called from the
/// calling thread about 200 times. Stops when *cancel becomes true and throws TrainingCancelled
/// (nothing is written). UserError when the session has nothing to train on.
store::TrainingRecord TrainSessionMethod(
    const store::Session& session, const std::string& method, const SessionTrainingOptions& options,
    const std::function<void(const TrainingProgress&)>& on_progress = {},
    const std::atomic<bool>* cancel = nullptr);

/// The sample counts of the session's kept demonstrations (neither bad nor damaged), in order.
std::vector<int64_t> KeptDemoLengths(const store::Session& session);

/// What to tell the teacher of the session's slow kept takes before training
/// (teach::SlowTakesWarning), or "".
std::string SlowTakesWarningOf(const store::Session& session);

/// How many steps the session's rollouts run: the world's episode, or 1.5 times its longest kept
/// demonstration (experiments::RolloutSteps), which a person's slow takes ask for. `note` says
/// when the takes asked for more than the most a rollout is given.
int SessionRolloutSteps(const store::Session& session, const worlds::World& world,
                        std::string* note = nullptr);

/// Rolls `method`'s checkpoint out on `tests` new scenes of the session's simulated cell with the
/// beacons removed (scene i from Rng::Derive(seed, i)), writes the method's rollout summary and
/// returns it. When the world has a replay (World::ReplayState) and `keep_replay`, also writes
/// every step's state to the method's replay file (store/rollout_replay.h), before the summary,
/// which names it; otherwise an older replay file of the method is removed. UserError without a
/// checkpoint or a simulated world. `hooks` show progress or stop the rollouts
/// (experiments::EvaluationCancelled; nothing is written then).
store::RolloutSummary EvaluateSessionMethod(const store::Session& session,
                                            const std::string& method, int tests, uint64_t seed,
                                            bool keep_replay = true,
                                            const experiments::EvaluationHooks& hooks = {});

/// EvaluateSessionMethod for each of `methods`, side by side, one core each (a rollout batch
/// runs on one thread, and its outcome does not depend on what else runs), so on 2 cores two
/// methods take the slower one's time. `on_done(summary)` is called once per method as it
/// finishes, from that method's thread, one call at a time. Returns the summaries in the order of
/// `methods`. A method that fails does not stop the others (each keeps what it wrote); then the
/// first failure, in the order of `methods`, is rethrown. `on_step(i, done, steps)` reports
/// method i's progress, from its thread (calls for different methods may overlap); `cancel`
/// stops them all (experiments::EvaluationCancelled; a method that had finished keeps its
/// files).
std::vector<store::RolloutSummary> EvaluateSessionMethods(
    const store::Session& session, const std::vector<std::string>& methods, int tests,
    uint64_t seed, const std::function<void(const store::RolloutSummary&)>& on_done = {},
    const std::function<void(size_t method, int done, int steps)>& on_step = {},
    const std::atomic<bool>* cancel = nullptr);

/// The seeds a session trains and tests with unless told otherwise (derived from its own).
uint64_t DefaultTrainingSeed(const store::Session& session);
uint64_t DefaultTestSeed(const store::Session& session);

}  // namespace recon::cli
