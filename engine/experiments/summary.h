#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/experiments/experiment.h"

namespace recon::experiments {

/// Mean and standard error of one condition at one demonstration count.
struct ConditionSummary {
  std::string condition;
  std::string label;
  int demos = 0;
  double mean = 0;
  double sem = 0;
  int n = 0;         ///< runs that finished (diverged runs are excluded from the mean)
  int diverged = 0;  ///< runs whose loss became NaN or infinite
  int train_steps = 0;
  double mean_attempts = 0;
  double mean_train_seconds = 0;
  /// Worlds with a notion of success: the mean over runs of each run's success rate, and its
  /// standard error.
  double success_rate = 0;
  double success_sem = 0;
  std::map<std::string, double> details;  ///< mean over runs of RunResult::details
};

/// One summary per (demos, condition), in config order.
std::vector<ConditionSummary> Summarize(const ExperimentConfig& config,
                                        const ExperimentResult& result);

/// Writes, atomically, into `dir`: results.csv (one row per run and condition, the same bytes on
/// any machine for the same runs), timing.csv (how long each trained), summary.json,
/// `<world>.png` and `.svg` (bars with standard-error whiskers, like the paper's figures),
/// losses.png (the action loss of run 0 of each condition), and, when several demo counts were
/// run, data_efficiency.png. Returns the paths written, figure first.
std::vector<std::string> WriteExperimentOutputs(const ExperimentConfig& config,
                                                const ExperimentResult& result,
                                                const std::string& dir);

/// Where an experiment keeps the runs it has finished while it runs (WriteRunsSoFar).
constexpr const char* kRunsSoFarFile = "runs_so_far.csv";

/// Writes, atomically, `dir`/runs_so_far.csv: the runs finished so far, one row each as
/// results.csv has them (seeds included), in (demos, condition, run) order. Called after every
/// run, so an experiment killed or failed after an hour keeps every run it finished;
/// WriteExperimentOutputs removes the file once results.csv is in place.
void WriteRunsSoFar(std::vector<RunResult> finished, const std::string& dir);

}  // namespace recon::experiments
