#pragma once

#include <deque>
#include <vector>

namespace recon::teach {

/// How a stream of readings is doing over the last few seconds.
struct StreamStats {
  double rate_hz = 0;           ///< updates per second received
  double dropout_fraction = 0;  ///< expected updates that never came, over expected ones
  /// Spread of the readings: the square root of the summed per-coordinate variances (metres for
  /// a position). Meaningful while the thing measured stands still.
  double noise = 0;
  int received = 0;                ///< updates in the window
  double seconds_since_last = -1;  ///< -1 before the first update
};

/// Keeps the recent updates of one stream (a beacon, the camera, the arm's state) to tell the
/// teacher its health: rate, dropouts and noise. Fed with the device's timestamps (or the
/// simulation's clock), so it is exact under test; pure, no clock of its own.
class StreamHealth {
 public:
  /// `expected_rate_hz`: the rate the device is set to (a DWM1001 at 10 Hz); gaps longer than
  /// 1.5 periods count the updates missing in them as dropouts.
  explicit StreamHealth(double expected_rate_hz, double window_s = 3.0);

  /// An update at time `t_s` (seconds, non-decreasing) with its reading (may be empty).
  void Add(double t_s, const std::vector<float>& reading = {});
  /// The stats of the window ending at `now_s`.
  StreamStats Stats(double now_s) const;

 private:
  struct Update {
    double t_s;
    std::vector<float> reading;
  };
  void Forget(double now_s);

  double expected_rate_hz_;
  double window_s_;
  std::deque<Update> updates_;
};

}  // namespace recon::teach
