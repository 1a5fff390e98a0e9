#pragma once

#include <Eigen/Core>
#include <vector>

namespace recon::calib {

/// Whether a calibration fits a rotation about the vertical axis plus a planar offset (2-D, the
/// usual case for beacons lying on a table) or a full 3-D rotation and offset.
enum class FitDimension { k2D, k3D };

/// A rigid transform p_table = rotation * p_uwb + translation (no scale: both frames are metric).
struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const { return rotation * p + translation; }
  /// Rotation about z in radians (meaningful for a 2-D fit).
  double YawRad() const;
};

/// Least-squares rigid transform taking `from` onto `to`, with a proper rotation (never a
/// mirror). 3-D: Umeyama's method without scale. 2-D: the closed-form yaw about z and a planar
/// offset; the z offset is the mean z difference. Throws UserError if the points are too few
/// (2-D: 2, 3-D: 3), non-finite (naming the point), or degenerate (all in one place, or collinear
/// for 3-D).
RigidTransform FitRigid(const std::vector<Eigen::Vector3d>& from,
                        const std::vector<Eigen::Vector3d>& to, FitDimension dimension);

}  // namespace recon::calib
