#pragma once

#include <array>

namespace recon::worlds {

/// A point or vector in the plane (world units).
using Vec2 = std::array<double, 2>;

}  // namespace recon::worlds
