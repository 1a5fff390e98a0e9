#include "devices/tags/pinhole_camera.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace recon::tags {

CameraIntrinsics CameraIntrinsics::FromFovy(double fovy_deg, int width, int height) {
  if (!(fovy_deg > 0.0 && fovy_deg < 180.0)) {
    throw UserError("camera fovy must be in (0, 180) degrees, got " + std::to_string(fovy_deg));
  }
  if (width <= 0 || height <= 0) {
    throw UserError("camera image size must be positive, got " + std::to_string(width) + "x" +
                    std::to_string(height));
  }
  CameraIntrinsics intrinsics;
  intrinsics.fy = 0.5 * height / std::tan(0.5 * fovy_deg * M_PI / 180.0);
  intrinsics.fx = intrinsics.fy;
  intrinsics.cx = 0.5 * width;
  intrinsics.cy = 0.5 * height;
  intrinsics.width = width;
  intrinsics.height = height;
  return intrinsics;
}

PinholeCamera::PinholeCamera(const CameraIntrinsics& intrinsics,
                             const Eigen::Vector3d& position_table_m,
                             const Eigen::Matrix3d& table_R_cv)
    : intrinsics_(intrinsics), position_table_m_(position_table_m), table_R_cv_(table_R_cv) {
  if (!(intrinsics_.fx > 0.0 && intrinsics_.fy > 0.0)) {
    throw UserError("camera focal lengths must be positive, got fx=" +
                    std::to_string(intrinsics_.fx) + " fy=" + std::to_string(intrinsics_.fy));
  }
  const double orthogonality =
      (table_R_cv_.transpose() * table_R_cv_ - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(orthogonality < 1e-6 && std::abs(table_R_cv_.determinant() - 1.0) < 1e-6)) {
    throw UserError("camera orientation is not a rotation matrix (|R^T R - I| = " +
                    std::to_string(orthogonality) +
                    ", det = " + std::to_string(table_R_cv_.determinant()) + ")");
  }
}

PinholeCamera PinholeCamera::FromMujoco(double fovy_deg, int width, int height,
                                        const Eigen::Vector3d& position_table_m,
                                        const Eigen::Matrix3d& table_R_mujoco) {
  return PinholeCamera(CameraIntrinsics::FromFovy(fovy_deg, width, height), position_table_m,
                       CvFromMujocoRotation(table_R_mujoco));
}

Eigen::Matrix3d PinholeCamera::CvFromMujocoRotation(const Eigen::Matrix3d& table_R_mujoco) {
  return table_R_mujoco * Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
}

Eigen::Vector2d PinholeCamera::Project(const Eigen::Vector3d& point_table_m) const {
  const Eigen::Vector3d p = table_R_cv_.transpose() * (point_table_m - position_table_m_);
  return {intrinsics_.fx * p.x() / p.z() + intrinsics_.cx,
          intrinsics_.fy * p.y() / p.z() + intrinsics_.cy};
}

Eigen::Vector3d PinholeCamera::RayDirection(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector3d ray_cv((pixel.x() - intrinsics_.cx) / intrinsics_.fx,
                               (pixel.y() - intrinsics_.cy) / intrinsics_.fy, 1.0);
  return (table_R_cv_ * ray_cv).normalized();
}

Eigen::Vector3d PinholeCamera::IntersectHorizontalPlane(const Eigen::Vector2d& pixel,
                                                        double height_m) const {
  const Eigen::Vector3d direction = RayDirection(pixel);
  // A ray within ~0.06 degrees of the plane would put the hit point kilometres away.
  if (std::abs(direction.z()) < 1e-3) {
    throw UserError("the camera ray through pixel (" + std::to_string(pixel.x()) + ", " +
                    std::to_string(pixel.y()) +
                    ") runs parallel to the plane z = " + std::to_string(height_m) + " m");
  }
  const double distance = (height_m - position_table_m_.z()) / direction.z();
  if (distance <= 0.0) {
    throw UserError("the plane z = " + std::to_string(height_m) +
                    " m is behind the camera along the ray through pixel (" +
                    std::to_string(pixel.x()) + ", " + std::to_string(pixel.y()) + ")");
  }
  return position_table_m_ + distance * direction;
}

}  // namespace recon::tags
