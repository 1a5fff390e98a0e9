#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

namespace recon {

/// A monotonic clock that moves only when told to. The studio reads its time from one when a
/// script or a test plays it: each frame the script draws moves the clock one frame on and waits
/// for the studio to catch up, so a scripted person's takes (what it sees, how late it reacts,
/// how far the arm moved meanwhile) are the same on any CPU and under any load. Without one the
/// studio runs on std::chrono::steady_clock, as a person at the desk needs.
///
/// Thread-safe: one thread advances it, any thread reads it.
class SteppedClock {
 public:
  using time_point = std::chrono::steady_clock::time_point;
  using duration = std::chrono::steady_clock::duration;

  /// Starts where the steady clock is now, so its times mix with nothing else's by accident
  /// but print like them.
  SteppedClock() : now_(std::chrono::steady_clock::now().time_since_epoch().count()) {}

  time_point Now() const { return time_point(duration(now_.load(std::memory_order_acquire))); }
  void Advance(duration by) { now_.fetch_add(by.count(), std::memory_order_acq_rel); }

 private:
  std::atomic<duration::rep> now_;
};

}  // namespace recon
