#include "devices/camera/undistorter.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "devices/camera/opencv_image.h"
#include "engine/core/error.h"

namespace recon::camera {

struct Undistorter::State {
  CameraCalibration calibration;
  cv::Mat k, d;        // OpenCV convention (pixel centres on integers)
  cv::Mat map1, map2;  // fixed-point remap tables from initUndistortRectifyMap
};

namespace {

cv::Mat ToMat(const Eigen::Matrix3d& m) {
  cv::Mat out(3, 3, CV_64F);
  for (int i = 0; i < 9; ++i) out.at<double>(i / 3, i % 3) = m(i / 3, i % 3);
  return out;
}

}  // namespace

Undistorter::Undistorter(const CameraCalibration& calibration) : state_(std::make_unique<State>()) {
  if (calibration.image_width <= 0 || calibration.image_height <= 0) {
    throw UserError("cannot undistort: the calibration has no image size");
  }
  state_->calibration = calibration;
  state_->k = ToMat(calibration.camera_matrix);
  std::vector<double> d = calibration.distortion;
  if (d.empty()) d.assign(5, 0.0);
  state_->d = cv::Mat(d, true).reshape(1, 1);
  // The new camera matrix is the old one, so the undistorted image has exactly the intrinsics
  // the calibration file states (some corners of the view are lost or left black instead).
  cv::initUndistortRectifyMap(state_->k, state_->d, cv::noArray(), state_->k,
                              cv::Size(calibration.image_width, calibration.image_height), CV_16SC2,
                              state_->map1, state_->map2);
}

Undistorter::~Undistorter() = default;
Undistorter::Undistorter(Undistorter&&) noexcept = default;
Undistorter& Undistorter::operator=(Undistorter&&) noexcept = default;

const CameraCalibration& Undistorter::calibration() const { return state_->calibration; }

RgbImage Undistorter::Apply(const RgbImage& image) const {
  const CameraCalibration& c = state_->calibration;
  if (image.width != c.image_width || image.height != c.image_height) {
    throw UserError("cannot undistort a " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " frame with a calibration made for " +
                    std::to_string(c.image_width) + "x" + std::to_string(c.image_height));
  }
  const cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.rgb.data()));
  cv::Mat out;
  cv::remap(rgb, out, state_->map1, state_->map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  // remap keeps the channel order, so this "BGR" is RGB already; convert twice would swap.
  RgbImage result;
  result.width = out.cols;
  result.height = out.rows;
  result.rgb.assign(out.data, out.data + out.total() * 3);
  return result;
}

Eigen::Vector2d Undistorter::UndistortPixel(const Eigen::Vector2d& raw_px) const {
  // Our pixel centres sit at +0.5 of OpenCV's: shift in, undistort, shift back.
  std::vector<cv::Point2d> in{{raw_px.x() - 0.5, raw_px.y() - 0.5}}, out;
  // The default 5 fixed-point iterations leave a fraction of a pixel near the image corners of
  // a wide lens; iterate to convergence instead.
  cv::undistortPoints(
      in, out, state_->k, state_->d, cv::noArray(), state_->k,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-10));
  return {out[0].x + 0.5, out[0].y + 0.5};
}

Eigen::Vector2d Undistorter::DistortPixel(const Eigen::Vector2d& undistorted_px) const {
  const Eigen::Matrix3d& k = state_->calibration.camera_matrix;
  const double x = (undistorted_px.x() - 0.5 - k(0, 2)) / k(0, 0);
  const double y = (undistorted_px.y() - 0.5 - k(1, 2)) / k(1, 1);
  std::vector<cv::Point3d> ray{{x, y, 1.0}};
  std::vector<cv::Point2d> out;
  cv::projectPoints(ray, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), state_->k, state_->d, out);
  return {out[0].x + 0.5, out[0].y + 0.5};
}

}  // namespace recon::camera
