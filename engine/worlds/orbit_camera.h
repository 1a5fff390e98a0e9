#pragma once

#include <Eigen/Core>

namespace recon::worlds {

/// A camera circling a point of the scene, as a person watching the cell walks around it and
/// steps closer or back: MuJoCo's free camera (mjCAMERA_FREE), with its conventions. Azimuth 0
/// looks along +x, 90 along +y; a negative elevation looks down.
struct OrbitCamera {
  static constexpr double kMinElevation_deg = -89.0;
  static constexpr double kMaxElevation_deg = -5.0;
  static constexpr double kMinDistance_m = 0.3;
  static constexpr double kMaxDistance_m = 3.0;

  Eigen::Vector3d lookat = Eigen::Vector3d(0.45, 0.0, 0.05);
  double azimuth_deg = 0.0;
  double elevation_deg = -45.0;
  double distance_m = 1.3;

  /// Elevation and distance held within the limits above, azimuth wrapped into (-180, 180], and
  /// a non-finite value replaced by the default's: whatever a drag or a wheel asks for, the
  /// camera stays above the table, outside it and at a distance that shows something.
  OrbitCamera Clamped() const;
  /// Where the camera is, in the world frame.
  Eigen::Vector3d Position() const;
  /// Its orientation as MuJoCo's cameras have it: columns x (right), y (up) and z (backwards,
  /// the camera looks along -z), in the world frame.
  Eigen::Matrix3d Rotation() const;
  /// The unit directions on the table (x, y) that look like right and like up the screen (away
  /// from the viewer) in this view: where the arrow keys move the arm.
  Eigen::Vector2d TableRight() const;
  Eigen::Vector2d TableAway() const;
};

}  // namespace recon::worlds
