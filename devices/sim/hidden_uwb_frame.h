#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "engine/calib/rigid_fit.h"
#include "engine/core/rng.h"

namespace recon::sim {

/// Draws where an installer might have put the UWB anchors' frame relative to the table: the
/// simulated cell's hidden table -> UWB pose (SimulatedDwm1001Options::table_to_uwb), which
/// calibration must recover. Any heading, the table somewhere inside the default 2.4 x 1.8 m
/// anchor rectangle, and the anchors' zero 0.7-0.8 m below the table top.
///
/// Header-only so that the calibration procedure (devices/cell) and the simulated cell share it
/// without a link dependency between them. Draws exactly 4 numbers from `rng`.
inline calib::RigidTransform DrawHiddenUwbFrame(Rng& rng) {
  calib::RigidTransform t;
  const double yaw_rad = rng.Uniform(-M_PI, M_PI);
  t.rotation = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d table_centre_m(0.55, 0.0, 0.0);
  // One draw per statement: the order of evaluation of constructor arguments is unspecified, so
  // drawing inside Vector3d(...) would give other frames with other compilers. z, y, x is the
  // order GCC used when this was written that way, so existing seeds keep their frames.
  const double z_m = rng.Uniform(0.7, 0.8);
  const double y_m = rng.Uniform(0.7, 1.1);
  const double x_m = rng.Uniform(1.0, 1.4);
  t.translation = Eigen::Vector3d(x_m, y_m, z_m) - t.rotation * table_centre_m;
  return t;
}

/// The inverse pose, p_table = inverse.Apply(p_uwb): what a perfect calibration would find.
inline calib::RigidTransform Inverse(const calib::RigidTransform& t) {
  calib::RigidTransform inverse;
  inverse.rotation = t.rotation.transpose();
  inverse.translation = -(inverse.rotation * t.translation);
  return inverse;
}

}  // namespace recon::sim
