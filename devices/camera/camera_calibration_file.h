#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "devices/tags/pinhole_camera.h"

namespace recon::camera {

/// A camera's intrinsics and lens distortion exactly as OpenCV states them (cv::calibrateCamera,
/// the calibration sample, cv::FileStorage): pixel centres on integers, so the top-left pixel's
/// centre is (0, 0). tags::CameraIntrinsics puts it at (0.5, 0.5); ToIntrinsics converts.
struct CameraCalibration {
  int image_width = 0;
  int image_height = 0;
  /// [fx 0 cx; 0 fy cy; 0 0 1], OpenCV pixel convention.
  Eigen::Matrix3d camera_matrix = Eigen::Matrix3d::Identity();
  /// OpenCV's order: k1 k2 p1 p2 [k3 [k4 k5 k6 [s1 s2 s3 s4 [tx ty]]]]; 4, 5, 8, 12 or 14 values
  /// (or none: no distortion).
  std::vector<double> distortion;

  /// The pinhole intrinsics of the undistorted image in our convention (cx, cy + 0.5). Distortion
  /// is not part of them: undistort the image (Undistorter) before using them.
  tags::CameraIntrinsics ToIntrinsics() const;
  /// The inverse of ToIntrinsics, with no distortion.
  static CameraCalibration FromIntrinsics(const tags::CameraIntrinsics& intrinsics);
  /// True when every distortion coefficient is zero (or there are none).
  bool HasNoDistortion() const;
};

/// Reads a calibration YAML (or XML/JSON) file as cv::FileStorage writes it: keys image_width,
/// image_height, camera_matrix (3x3 opencv-matrix) and distortion_coefficients (1xN or Nx1 with
/// N in {4, 5, 8, 12, 14}). Plain {rows, cols, data} maps, as ROS camera_info files use, are
/// accepted too; other keys are ignored. Throws UserError naming the file and the missing or bad
/// key, or saying that the file is not a calibration file at all.
CameraCalibration ReadCameraCalibration(const std::string& path);

/// Writes `calibration` in the format ReadCameraCalibration (and OpenCV) reads, atomically.
/// Throws UserError naming the file if it cannot be written or the calibration is invalid
/// (non-positive size or focal length, a distortion count OpenCV does not know).
void WriteCameraCalibration(const std::string& path, const CameraCalibration& calibration);

}  // namespace recon::camera
