#pragma once

#include <array>

namespace recon::teach {

/// Fine control for a person at the keys: what each held key (or one tapped between two control
/// periods) commands in the next period, as a share of the teleop's full speed. A key tapped
/// and let go, even between two periods, moves one small step (kTapShare of a period at full
/// speed: 3 mm at the studio's 0.1 m/s and 10 Hz); a key held starts slow (kFineShare: 3 cm/s)
/// and speeds up to full speed over kRampSeconds, so a person can line the gripper up to the
/// millimetre and still cross the table in a few seconds. One channel per key pair (screen
/// right, screen up, raise, wrist turn), each -1, 0 or +1 as the keys send it.
class KeyRamp {
 public:
  static constexpr int kChannels = 4;
  static constexpr double kTapShare = 0.3;
  static constexpr double kFineShare = 0.3;
  static constexpr double kRampSeconds = 0.6;

  /// A key change on `channel` at `now_s`: -1, 0 or +1 (anything else counts by its sign).
  void Set(int channel, float value, double now_s);
  /// The signed share of full speed each channel commands for the period starting at `now_s`;
  /// a tap not yet moved is used up here.
  std::array<float, kChannels> Period(double now_s);
  /// Every key let go and no tap pending (between takes).
  void Clear();

 private:
  struct Channel {
    int held = 0;  ///< the key held now
    double held_since_s = 0;
    int tap = 0;  ///< a press since the last period, to move by at least a step
  };
  std::array<Channel, kChannels> channels_{};
};

}  // namespace recon::teach
