#include "engine/teach/homing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/core/error.h"

namespace recon::teach {

namespace {

void RequirePositive(double value, const char* field) {
  if (!std::isfinite(value) || value <= 0) {
    throw UserError(std::string("homing: ") + field + " must be a positive number");
  }
}

}  // namespace

void HomingLimits::Validate() const {
  RequirePositive(max_speed_rad_s, "max_speed_rad_s");
  RequirePositive(gain_per_s, "gain_per_s");
  RequirePositive(tolerance_rad, "tolerance_rad");
  RequirePositive(max_distance_rad, "max_distance_rad");
}

double HomingDistance(const std::array<double, 6>& q_rad, const std::array<double, 6>& home_rad) {
  double largest = 0;
  for (int i = 0; i < 6; ++i) {
    const double d = std::abs(home_rad[i] - q_rad[i]);
    if (!std::isfinite(d)) return std::numeric_limits<double>::infinity();
    largest = std::max(largest, d);
  }
  return largest;
}

std::optional<std::array<double, 6>> HomingVelocity(const std::array<double, 6>& q_rad,
                                                    const std::array<double, 6>& home_rad,
                                                    const HomingLimits& limits) {
  limits.Validate();
  for (int i = 0; i < 6; ++i) {
    const double d = home_rad[i] - q_rad[i];
    if (!std::isfinite(d) || std::abs(d) > limits.max_distance_rad) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    "joint %d is %.2f rad from its home pose (at most %.2f is driven there by "
                    "itself): bring the arm near home with the pendant first",
                    i + 1, std::abs(d), limits.max_distance_rad);
      throw UserError(text);
    }
  }
  if (HomingDistance(q_rad, home_rad) <= limits.tolerance_rad) return std::nullopt;
  std::array<double, 6> v{};
  double fastest = 0;
  for (int i = 0; i < 6; ++i) {
    v[i] = limits.gain_per_s * (home_rad[i] - q_rad[i]);
    fastest = std::max(fastest, std::abs(v[i]));
  }
  if (fastest > limits.max_speed_rad_s) {
    const double scale = limits.max_speed_rad_s / fastest;
    for (double& x : v) x *= scale;
  }
  return v;
}

}  // namespace recon::teach
