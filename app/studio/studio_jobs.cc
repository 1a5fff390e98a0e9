#include "app/studio/studio_jobs.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "devices/cell/sim_calibration.h"
#include "engine/calib/calibration.h"
#include "engine/core/parallel_for.h"
#include "engine/experiments/evaluation.h"
#include "engine/teach/workflow.h"

namespace recon::studio {

namespace fs = std::filesystem;

void CalibrateCell(JobThread& jobs, uint64_t seed, int points, const std::string& path) {
  cell::SimCalibrationOptions calibration;
  calibration.seed = seed;
  calibration.points = points;
  const cell::SimCalibrationResult result =
      cell::RunSimulatedCalibration(calibration, [&](int done, int) {
        jobs.Update([&](JobState& state) { state.calibration_points = done; });
      });
  calib::SaveCalibration(result.report, path);
}

std::string TrainMethods(JobThread& jobs, const store::Session& session,
                         const cli::SessionTrainingOptions& options,
                         const std::vector<std::string>& methods) {
  jobs.Update([&](JobState& state) {
    for (const std::string& method : methods) {
      ui::TrainingView view;
      view.method = method;
      view.label = method == teach::kBaselineMethod ? "Baseline" : "RECON";
      view.steps = options.steps;
      view.loss = options.loss;
      state.training.push_back(view);
    }
  });
  // Each trainer runs on one core (learner.h), so the methods train side by side, one thread
  // each: on 2 cores Train-to-Rollouts takes the slowest method's time, not the sum.
  std::vector<int> cancelled_at(methods.size(), -1);
  const auto train_one = [&](size_t i) {
    try {
      const auto start = std::chrono::steady_clock::now();
      cli::TrainSessionMethod(
          session, methods[i], options,
          [&](const cli::TrainingProgress& p) {
            jobs.Update([&](JobState& state) {
              ui::TrainingView& view = state.training[i];
              view.label = p.label;
              view.running = true;
              view.step = p.step;
              view.seconds =
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
              if (!p.curve_point) return;
              view.loss_step.push_back(static_cast<float>(p.step));
              view.action_loss.push_back(p.latest.action_loss);
              if (methods[i] == teach::kReconMethod) {
                view.beacon_loss.push_back(p.latest.beacon_loss);
              }
              view.total_loss.push_back(p.latest.total_loss);
            });
          },
          jobs.cancel_flag());
      jobs.Update([&](JobState& state) {
        state.training[i].running = false;
        state.training[i].done = true;
      });
    } catch (const cli::TrainingCancelled& e) {
      cancelled_at[i] = e.step();
      jobs.Update([&](JobState& state) { state.training[i].running = false; });
    } catch (...) {
      jobs.Update([&](JobState& state) { state.training[i].running = false; });
      throw;
    }
  };
  // What one method's failure says is reported; a method that finished keeps its checkpoint.
  RethrowFirst(ParallelForEachCatching(
      methods.size(), std::max(1u, std::thread::hardware_concurrency()), train_one));
  // A cancel is what the teacher asked for, not an error: say what was kept.
  std::string saved, stopped;
  const std::vector<ui::TrainingView> views = jobs.Peek().training;
  for (size_t i = 0; i < methods.size(); ++i) {
    std::string& list = cancelled_at[i] < 0 ? saved : stopped;
    list += (list.empty() ? "" : ", ") + views[i].label;
    if (cancelled_at[i] >= 0) list += " at step " + std::to_string(cancelled_at[i]);
  }
  if (stopped.empty()) return "Trained.";
  return "Training cancelled (" + stopped + "); nothing of it was saved" +
         (saved.empty() ? "" : "; " + saved + " had finished and was saved") + ".";
}

std::string RollOutTrainedMethods(JobThread& jobs, const store::Session& session, int tests) {
  std::vector<std::string> methods;
  for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
    if (fs::exists(session.CheckpointPath(method))) methods.push_back(method);
  }
  std::vector<int> done(methods.size(), 0);
  const auto on_step = [&](size_t i, int steps_done, int steps) {
    jobs.Update([&](JobState& state) {
      done[i] = steps_done;  // under the job's lock, as every method's thread writes here
      state.rollout_steps_total = steps * static_cast<int>(methods.size());
      state.rollout_steps_done = 0;
      for (int d : done) state.rollout_steps_done += d;
    });
  };
  // Side by side, one core each, as they train.
  try {
    cli::EvaluateSessionMethods(session, methods, tests, cli::DefaultTestSeed(session), {}, on_step,
                                jobs.cancel_flag());
  } catch (const experiments::EvaluationCancelled&) {
    return "Rollouts cancelled; a method that had not finished keeps its rollouts from before.";
  }
  return "Rollouts done.";
}

}  // namespace recon::studio
