#pragma once

#include <chrono>

namespace recon::devices {

/// Where device timestamps come from. The simulated cell uses a clock that advances with the
/// simulation; real devices use the steady wall clock. Seconds since an arbitrary start.
class Clock {
 public:
  virtual ~Clock() = default;
  virtual double NowSeconds() const = 0;
};

/// A clock that only moves when told to: simulated time.
class ManualClock final : public Clock {
 public:
  double NowSeconds() const override { return now_s_; }
  void Advance(double seconds) { now_s_ += seconds; }
  void Set(double seconds) { now_s_ = seconds; }

 private:
  double now_s_ = 0.0;
};

/// The host's steady clock, for real devices: seconds since this object was made.
class SteadyClock final : public Clock {
 public:
  double NowSeconds() const override {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace recon::devices
