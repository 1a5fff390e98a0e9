#pragma once

#include <string>
#include <vector>

#include "app/cli/session_training.h"
#include "app/studio/job_thread.h"
#include "engine/store/session.h"

namespace recon::studio {

// The bodies of the studio's long jobs, run on its JobThread. They only read the session; what
// they produce is applied to it on the cell thread afterwards.

/// Runs the simulated calibration (`points` poses, `seed`) with progress in the job state and
/// saves the result to `path`.
void CalibrateCell(JobThread& jobs, uint64_t seed, int points, const std::string& path);

/// Trains `methods` side by side (one thread each, up to the number of cores), with live losses in the job state's training views;
/// returns the finished views. Throws UserError when cancelled.
std::vector<ui::TrainingView> TrainMethods(JobThread& jobs, const store::Session& session,
                                           const cli::SessionTrainingOptions& options,
                                           const std::vector<std::string>& methods);

/// Rolls out every trained method on `tests` new scenes with the beacons removed.
void RollOutTrainedMethods(const store::Session& session, int tests);

}  // namespace recon::studio
