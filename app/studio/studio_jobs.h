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

/// Trains `methods` side by side (one thread each, up to the number of cores), with live losses
/// in the job state's training views. Returns what happened, for the status line: "Trained.",
/// or, when the job was cancelled, which methods finished (and were saved) before it and where
/// the others stopped (nothing of them saved). Rethrows the first failure that was not a cancel;
/// a method that finished keeps its checkpoint either way.
std::string TrainMethods(JobThread& jobs, const store::Session& session,
                         const cli::SessionTrainingOptions& options,
                         const std::vector<std::string>& methods);

/// Rolls out every trained method on `tests` new scenes with the beacons removed, side by side,
/// with their progress in the job state. Returns what happened, for the status line: "Rollouts
/// done.", or, when the job was cancelled, that a method stopped half-way wrote nothing (it
/// keeps its rollouts from before).
std::string RollOutTrainedMethods(JobThread& jobs, const store::Session& session, int tests);

}  // namespace recon::studio
