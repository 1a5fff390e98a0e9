#include "app/studio/job_thread.h"

#include <memory>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"

namespace recon::studio {

const char* JobKindName(JobKind kind) {
  switch (kind) {
    case JobKind::kCalibration:
      return "calibration";
    case JobKind::kTraining:
      return "training";
    case JobKind::kRollouts:
      return "rollouts";
    case JobKind::kProbe:
      return "probe";
  }
  return "job";
}

JobThread::JobThread() {
  thread_ = std::thread([this] {
    const std::unique_ptr<worlds::SceneRenderer> keep = render::MujocoRendererFactory()();
    Loop();
  });
}

JobThread::~JobThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  cancel_ = true;
  wake_.notify_all();
  thread_.join();
}

bool JobThread::Running() const {
  std::lock_guard<std::mutex> lock(mutex_);
  // A failed job's error counts as a result: until it is taken and shown, the screens still
  // show the job running, and a script's wait-idle that ended there clicked on that stale view.
  return state_.running || state_.finish != nullptr || !state_.error.empty() || work_ != nullptr;
}

std::optional<JobKind> JobThread::RunningKind() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_.running || work_ != nullptr ? state_.kind : std::nullopt;
}

void JobThread::Start(JobKind kind, Work work) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (state_.running || work_ != nullptr) {
    throw UserError(std::string("wait for the ") + JobKindName(*state_.kind) + " to finish");
  }
  cancel_ = false;
  state_ = {};
  state_.kind = kind;
  state_.running = true;
  work_ = std::move(work);
  wake_.notify_all();
}

void JobThread::Update(const std::function<void(JobState&)>& change) {
  std::lock_guard<std::mutex> lock(mutex_);
  change(state_);
}

JobState JobThread::Peek() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_;
}

JobState JobThread::Take() {
  std::lock_guard<std::mutex> lock(mutex_);
  JobState copy = state_;
  state_.finish = nullptr;
  state_.error.clear();
  return copy;
}

void JobThread::Loop() {
  while (true) {
    Work work;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return quit_ || work_ != nullptr; });
      if (quit_) return;
      work = std::move(work_);
      work_ = nullptr;
    }
    std::function<void()> finish;
    std::string error;
    try {
      finish = work(*this);
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    state_.running = false;
    state_.error = error;
    state_.finish = std::move(finish);
  }
}

}  // namespace recon::studio
