#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "engine/safety/guarded_arm.h"

namespace recon::safety {

/// Runs a GuardedArm's watchdog on its own thread, for a real arm whose control loop may stall
/// (a slow policy, a hung GUI): every `period_ms` it calls CheckWatchdog(), so the arm is told to
/// stop within timeout + period of the last command. The simulated cell does not need one: it
/// checks before every physics step. Stops and joins in the destructor.
class ArmWatchdog {
 public:
  explicit ArmWatchdog(GuardedArm& arm, int period_ms = 20);
  ~ArmWatchdog();
  ArmWatchdog(const ArmWatchdog&) = delete;
  ArmWatchdog& operator=(const ArmWatchdog&) = delete;

  /// Times the watchdog stopped the arm.
  int64_t trips() const { return trips_; }

 private:
  void Run();

  GuardedArm& arm_;
  int period_ms_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::atomic<int64_t> trips_{0};
  std::thread thread_;
};

}  // namespace recon::safety
