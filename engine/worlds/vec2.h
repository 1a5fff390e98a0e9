#pragma once

#include <array>
#include <cmath>

namespace recon::worlds {

/// A point or vector in the plane (world units).
using Vec2 = std::array<double, 2>;

inline double Distance(const Vec2& a, const Vec2& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

}  // namespace recon::worlds
