#include "engine/safety/arm_watchdog.h"

#include <chrono>

namespace recon::safety {

ArmWatchdog::ArmWatchdog(GuardedArm& arm, int period_ms)
    : arm_(arm), period_ms_(period_ms), thread_([this] { Run(); }) {}

ArmWatchdog::~ArmWatchdog() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ArmWatchdog::Run() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(period_ms_), [this] { return stop_; })) {
    lock.unlock();
    try {
      if (arm_.CheckWatchdog()) ++trips_;
    } catch (...) {
      // The arm is gone (its driver throws); the control loop will hear it on its next call.
    }
    lock.lock();
  }
}

}  // namespace recon::safety
