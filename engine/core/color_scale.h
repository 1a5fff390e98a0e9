#pragma once

// The one sequential colour scale the project draws values with (heat maps in reports and in the
// studio), so a value has the same colour wherever a person sees it.

#include <algorithm>
#include <array>
#include <cstddef>

namespace recon {

/// Viridis (perceptually even, readable in grey and by colour-blind readers) at five stops,
/// interpolated linearly: t in [0, 1] (clamped) to sRGB components in [0, 1].
inline std::array<double, 3> SequentialColor(double t) {
  static constexpr std::array<std::array<double, 3>, 5> kStops = {{{0.267, 0.005, 0.329},
                                                                   {0.231, 0.322, 0.545},
                                                                   {0.129, 0.569, 0.549},
                                                                   {0.369, 0.788, 0.384},
                                                                   {0.993, 0.906, 0.144}}};
  t = std::clamp(t, 0.0, 1.0) * static_cast<double>(kStops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(t), kStops.size() - 2);
  const double f = t - static_cast<double>(i);
  std::array<double, 3> c{};
  for (size_t k = 0; k < 3; ++k) c[k] = kStops[i][k] + f * (kStops[i + 1][k] - kStops[i][k]);
  return c;
}

}  // namespace recon
