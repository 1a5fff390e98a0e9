#include "app/studio/studio_controller.h"

#include <chrono>
#include <future>

#include "app/studio/studio_cell.h"

namespace recon::studio {

using Clock = std::chrono::steady_clock;

StudioController::StudioController(const StudioOptions& options)
    : options_(options), cell_(std::make_unique<StudioCell>(options)) {
  // The session and the world are made on the cell thread, which owns their GL context and
  // MuJoCo data; errors come back here so the app can report them before showing a window.
  std::promise<void> started;
  std::future<void> ready = started.get_future();
  cell_thread_ = std::thread([this, &started] {
    try {
      cell_->Start();
      ui::StudioSnapshot first;
      cell_->Publish(first);
      {
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        snapshot_ = std::move(first);
      }
      started.set_value();
    } catch (...) {
      cell_.reset();  // on this thread, like everything it made
      started.set_exception(std::current_exception());
      return;
    }
    RunCellThread();
    // The cell's GL contexts and MuJoCo data were made on this thread and must be freed here:
    // a context left current on an exited thread cannot be made current anywhere else.
    cell_.reset();
  });
  try {
    ready.get();
  } catch (...) {
    cell_thread_.join();
    throw;
  }
}

StudioController::~StudioController() {
  stop_ = true;
  if (cell_thread_.joinable()) cell_thread_.join();
}

void StudioController::RunCellThread() {
  constexpr auto kFrame = std::chrono::milliseconds(33);  // camera and snapshot at ~30 Hz
  auto next_publish = cell_->Now();
  Clock::time_point last_pass{};
  while (!stop_) {
    // One time for the whole pass: on a SteppedClock, what a pass does depends on that time
    // alone, not on when the clock is moved on meanwhile.
    cell_->BeginPass();
    const Clock::time_point now = cell_->Now();
    if (options_.clock && now == last_pass && cell_->Driving() && Settled()) {
      // Driving on a clock that has not moved: nothing to step until it does.
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    last_pass = now;
    const std::vector<ui::StudioCommand> commands = commands_.Drain();
    for (const ui::StudioCommand& command : commands) {
      try {
        cell_->Handle(command);
      } catch (const std::exception& e) {
        cell_->AddError(e.what());  // shown on screen until dismissed
      }
    }
    try {
      cell_->Tick();
    } catch (const std::exception& e) {
      cell_->AddError(e.what());
    }
    const bool busy = cell_->Busy();
    if (now >= next_publish || !commands.empty() || busy != published_busy_) {
      ui::StudioSnapshot fresh;
      try {
        cell_->Publish(fresh);
      } catch (const std::exception& e) {
        // A file of the session went bad under us (deleted, edited): say so, keep running.
        cell_->AddError(e.what());
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        snapshot_.errors = cell_->errors();
        published_busy_ = busy;
        handled_ += commands.size();
        passed_ = now;
        next_publish = now + kFrame;
        continue;
      }
      // The snapshot, whether anything runs and how many commands it reflects change together,
      // so Idle() and Settled() never pair an old state with a new count.
      std::lock_guard<std::mutex> lock(snapshot_mutex_);
      snapshot_ = std::move(fresh);
      published_busy_ = busy;
      handled_ += commands.size();
      next_publish = now + kFrame;
    }
    {
      std::lock_guard<std::mutex> lock(snapshot_mutex_);
      passed_ = now;
    }
    // A recording steps the simulation from this loop (as fast as it can with --fast); anything
    // else only waits for commands, a job's end or the next frame.
    if (!cell_->Driving()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void StudioController::Push(ui::StudioCommand command) {
  {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    ++pushed_;
  }
  commands_.Push(std::move(command));
}

ui::StudioSnapshot StudioController::Snapshot() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return snapshot_;
}

bool StudioController::Idle() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return !published_busy_ && handled_ == pushed_;
}

bool StudioController::CaughtUp(Clock::time_point t) const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return passed_ >= t;
}

bool StudioController::Settled() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return handled_ == pushed_;
}

}  // namespace recon::studio
