#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The studio's long activities.
enum class JobKind { kCalibration, kTraining, kRollouts, kProbe };

/// The activity as the studio's messages name it ("calibration", "training", "rollouts",
/// "probe").
const char* JobKindName(JobKind kind);

/// What the studio shows of a long activity on the job thread.
struct JobState {
  std::optional<JobKind> kind;  ///< none before the first job
  bool running = false;
  int calibration_points = 0;
  std::vector<ui::TrainingView> training;
  /// The rollouts' steps done and to do, summed over the methods rolling out.
  int rollout_steps_done = 0, rollout_steps_total = 0;
  /// The probe's phase and its units done and to do.
  std::string probe_phase;
  int probe_done = 0, probe_total = 0;
  std::string error;
  std::function<void()> finish;  ///< run on the cell thread when the job is over
};

/// The studio's long activities (calibration, training, rollouts), one at a time, on one thread
/// that lives as long as the studio. The cell thread starts a job, peeks at its state for the
/// snapshot and, once it is over, applies its result (only the cell thread changes the session).
///
/// The thread holds a renderer handle from start to end, so the calibration and rollout worlds
/// it makes share one EGL context that lives as long as the thread: no context is made or
/// dropped while other threads render (Mesa's llvmpipe has crashed on that).
class JobThread {
 public:
  /// A job: gets this object to report progress, returns what to do on the cell thread after.
  using Work = std::function<std::function<void()>(JobThread&)>;

  JobThread();
  ~JobThread();
  JobThread(const JobThread&) = delete;
  JobThread& operator=(const JobThread&) = delete;

  /// Running, queued, or finished but its result not yet taken (so the studio never looks idle
  /// between the two).
  bool Running() const;
  /// The job that is running or queued, if any.
  std::optional<JobKind> RunningKind() const;
  /// Queues `work`; UserError if a job runs.
  void Start(JobKind kind, Work work);
  void Cancel() { cancel_ = true; }
  const std::atomic<bool>* cancel_flag() const { return &cancel_; }
  /// Changes the state under the lock (progress reports from the job).
  void Update(const std::function<void(JobState&)>& change);
  /// A copy of the state, leaving a finished job's result in place.
  JobState Peek() const;
  /// A copy of the state; takes a finished job's result (finish and error) out of it.
  JobState Take();

 private:
  void Loop();

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  JobState state_;
  Work work_;
  bool quit_ = false;
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace recon::studio
