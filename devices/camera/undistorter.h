#pragma once

#include <Eigen/Core>
#include <memory>

#include "devices/camera/camera_calibration_file.h"
#include "engine/core/image.h"

namespace recon::camera {

/// Removes lens distortion from a calibrated camera's frames. The undistorted image keeps the
/// size and camera matrix of the calibration, so calibration.ToIntrinsics() is its pinhole model
/// and TagDetector / TableLocator can work on it directly. Pixel coordinates here follow
/// tags::CameraIntrinsics (pixel centres at +0.5).
class Undistorter {
 public:
  /// Precomputes the remap tables (a few ms for 640 x 480). Throws UserError for a calibration
  /// with a non-positive size.
  explicit Undistorter(const CameraCalibration& calibration);
  ~Undistorter();
  Undistorter(Undistorter&&) noexcept;
  Undistorter& operator=(Undistorter&&) noexcept;

  /// The undistorted frame (bilinear). Throws UserError when the image size is not the
  /// calibration's: a calibration holds for one resolution only.
  RgbImage Apply(const RgbImage& image) const;

  /// Where a point of the raw image appears in the undistorted one.
  Eigen::Vector2d UndistortPixel(const Eigen::Vector2d& raw_px) const;
  /// Where a point of the undistorted image was in the raw one (the lens model itself).
  Eigen::Vector2d DistortPixel(const Eigen::Vector2d& undistorted_px) const;

  const CameraCalibration& calibration() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace recon::camera
