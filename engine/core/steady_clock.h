#pragma once

#include <chrono>

namespace recon {

/// Seconds on the monotonic clock (std::chrono::steady_clock): what the devices stamp their
/// readings with and measure timeouts against, unaffected by changes of the wall clock.
inline double SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace recon
