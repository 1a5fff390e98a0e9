#include "engine/worlds/orbit_camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace recon::worlds {

namespace {

constexpr double kPi = 3.14159265358979323846;
double Radians(double degrees) { return degrees * kPi / 180.0; }

}  // namespace

OrbitCamera OrbitCamera::Clamped() const {
  const OrbitCamera defaults;
  OrbitCamera c = *this;
  if (!c.lookat.allFinite()) c.lookat = defaults.lookat;
  if (!std::isfinite(c.azimuth_deg)) c.azimuth_deg = defaults.azimuth_deg;
  if (!std::isfinite(c.elevation_deg)) c.elevation_deg = defaults.elevation_deg;
  if (!std::isfinite(c.distance_m)) c.distance_m = defaults.distance_m;
  c.azimuth_deg = std::remainder(c.azimuth_deg, 360.0);
  if (c.azimuth_deg <= -180.0) c.azimuth_deg += 360.0;
  c.elevation_deg = std::clamp(c.elevation_deg, kMinElevation_deg, kMaxElevation_deg);
  c.distance_m = std::clamp(c.distance_m, kMinDistance_m, kMaxDistance_m);
  return c;
}

// mjv_updateCamera's free camera: forward (cos e cos a, cos e sin a, sin e), up (-sin e cos a,
// -sin e sin a, cos e), the head `distance` behind the look-at point along forward.
Eigen::Matrix3d OrbitCamera::Rotation() const {
  const double a = Radians(azimuth_deg), e = Radians(elevation_deg);
  const Eigen::Vector3d forward(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
  const Eigen::Vector3d up(-std::sin(e) * std::cos(a), -std::sin(e) * std::sin(a), std::cos(e));
  Eigen::Matrix3d r;
  r.col(0) = forward.cross(up);
  r.col(1) = up;
  r.col(2) = -forward;
  return r;
}

Eigen::Vector3d OrbitCamera::Position() const { return lookat + distance_m * Rotation().col(2); }

Eigen::Vector2d OrbitCamera::TableRight() const {
  const double a = Radians(azimuth_deg);
  return {std::sin(a), -std::cos(a)};
}

Eigen::Vector2d OrbitCamera::TableAway() const {
  const double a = Radians(azimuth_deg);
  return {std::cos(a), std::sin(a)};
}

}  // namespace recon::worlds
