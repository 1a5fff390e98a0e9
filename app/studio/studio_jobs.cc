#include "app/studio/studio_jobs.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <filesystem>
#include <thread>

#include "devices/cell/sim_calibration.h"
#include "engine/calib/calibration.h"
#include "engine/core/parallel_for.h"
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

std::vector<ui::TrainingView> TrainMethods(JobThread& jobs, const store::Session& session,
                                           const cli::SessionTrainingOptions& options,
                                           const std::vector<std::string>& methods) {
  jobs.Update([&](JobState& state) {
    for (const std::string& method : methods) {
      ui::TrainingView view;
      view.method = method;
      view.label = method == teach::kBaselineMethod ? "Baseline" : "RECON";
      view.steps = options.steps;
      state.training.push_back(view);
    }
  });
  // Each trainer runs on one core (learner.h), so the methods train side by side, one thread
  // each: on 2 cores Train-to-Rollouts takes the slowest method's time, not the sum.
  std::vector<std::exception_ptr> errors(methods.size());
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
    } catch (...) {
      errors[i] = std::current_exception();
      jobs.Update([&](JobState& state) { state.training[i].running = false; });
    }
  };
  ParallelFor(methods.size(), std::max(1u, std::thread::hardware_concurrency()), train_one);
  // What one method's failure says is reported; a method that finished keeps its checkpoint.
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return jobs.Peek().training;
}

void RollOutTrainedMethods(const store::Session& session, int tests) {
  for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
    if (fs::exists(session.CheckpointPath(method))) {
      cli::EvaluateSessionMethod(session, method, tests, cli::DefaultTestSeed(session));
    }
  }
}

}  // namespace recon::studio
