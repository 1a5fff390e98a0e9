#pragma once

#include <Eigen/Core>

namespace recon::tags {

/// Pinhole intrinsics in pixels, no distortion (a simulated camera has none; a real one is
/// undistorted first). Pixel coordinates follow TagDetection: x = column, y = row (down), and
/// pixel (c, r) covers [c, c + 1) x [r, r + 1), so its centre is at (c + 0.5, r + 0.5).
struct CameraIntrinsics {
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  int width = 0;
  int height = 0;

  /// The intrinsics of a MuJoCo camera with vertical field of view `fovy_deg` rendering
  /// width x height pixels: fy = (height / 2) / tan(fovy / 2), fx = fy (square pixels),
  /// cx = width / 2, cy = height / 2. MuJoCo's frustum spans the whole viewport, whose edges are
  /// at 0 and width in the convention above, so the optical axis meets the image at exactly
  /// (width / 2, height / 2) - not at ((width - 1) / 2, (height - 1) / 2), which is where it would
  /// be if pixel centres sat on integers (OpenCV's convention). Throws UserError for a fovy
  /// outside (0, 180) or a non-positive size.
  static CameraIntrinsics FromFovy(double fovy_deg, int width, int height);
};

/// A calibrated camera: intrinsics plus its pose in the table frame.
///
/// Two camera-frame conventions meet here. AprilTag (like OpenCV) uses x right, y down, z out of
/// the lens; MuJoCo cameras look along their -z axis with +x right and +y up in the image. The
/// same physical camera therefore has table_R_cv = table_R_mujoco * diag(1, -1, -1): x is shared
/// and y, z flip. Everything below stores the AprilTag/OpenCV form.
class PinholeCamera {
 public:
  /// `table_R_cv`: columns are the camera's x (right), y (down), z (forward) axes in the table
  /// frame; `position_table_m`: the optical centre. Throws UserError if table_R_cv is not a
  /// rotation (orthonormal, determinant +1, within 1e-6).
  PinholeCamera(const CameraIntrinsics& intrinsics, const Eigen::Vector3d& position_table_m,
                const Eigen::Matrix3d& table_R_cv);

  /// A MuJoCo camera: vertical fov, image size, and its pose as MuJoCo reports it once expressed
  /// in the table frame (cam_xpos and cam_xmat, the latter row-major in mjData, whose columns
  /// are the camera's x, y, z axes; the camera looks along -z).
  static PinholeCamera FromMujoco(double fovy_deg, int width, int height,
                                  const Eigen::Vector3d& position_table_m,
                                  const Eigen::Matrix3d& table_R_mujoco);

  /// Converts a MuJoCo camera orientation (-z forward, +y up) to the AprilTag/OpenCV one
  /// (+z forward, +y down) for the same camera.
  static Eigen::Matrix3d CvFromMujocoRotation(const Eigen::Matrix3d& table_R_mujoco);

  /// The pixel where a table-frame point appears. The point must be in front of the camera.
  Eigen::Vector2d Project(const Eigen::Vector3d& point_table_m) const;

  /// The unit direction, in the table frame, of the ray from the optical centre through `pixel`.
  Eigen::Vector3d RayDirection(const Eigen::Vector2d& pixel) const;

  /// Where the ray through `pixel` meets the horizontal plane z = height_m of the table frame.
  /// Throws UserError when the ray runs parallel to the plane or meets it behind the camera.
  Eigen::Vector3d IntersectHorizontalPlane(const Eigen::Vector2d& pixel, double height_m) const;

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  const Eigen::Vector3d& position_table_m() const { return position_table_m_; }
  const Eigen::Matrix3d& table_R_cv() const { return table_R_cv_; }

 private:
  CameraIntrinsics intrinsics_;
  Eigen::Vector3d position_table_m_;
  Eigen::Matrix3d table_R_cv_;
};

}  // namespace recon::tags
