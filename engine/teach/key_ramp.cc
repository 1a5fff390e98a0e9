#include "engine/teach/key_ramp.h"

#include <algorithm>

namespace recon::teach {

void KeyRamp::Set(int channel, float value, double now_s) {
  if (channel < 0 || channel >= kChannels) return;
  Channel& c = channels_[channel];
  const int held = value > 0 ? 1 : (value < 0 ? -1 : 0);
  if (held != 0 && held != c.held) {
    c.held_since_s = now_s;
    c.tap = held;  // moves by at least a step, however soon it is let go
  }
  c.held = held;
}

std::array<float, KeyRamp::kChannels> KeyRamp::Period(double now_s) {
  std::array<float, kChannels> share{};
  for (int k = 0; k < kChannels; ++k) {
    Channel& c = channels_[k];
    if (c.held != 0) {
      const double ramp = std::clamp((now_s - c.held_since_s) / kRampSeconds, 0.0, 1.0);
      const double speed =
          std::max(kFineShare + (1.0 - kFineShare) * ramp, c.tap != 0 ? kTapShare : 0.0);
      share[k] = static_cast<float>(c.held * speed);
    } else if (c.tap != 0) {
      share[k] = static_cast<float>(c.tap * kTapShare);
    }
    c.tap = 0;
  }
  return share;
}

void KeyRamp::Clear() { channels_ = {}; }

}  // namespace recon::teach
