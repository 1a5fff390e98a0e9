#include "devices/camera/undistorter.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"

namespace recon::camera {
namespace {

// A wide-ish lens with strong barrel distortion and a little tangential distortion.
CameraCalibration Lens() {
  CameraCalibration c;
  c.image_width = 640;
  c.image_height = 480;
  c.camera_matrix << 500.0, 0.0, 319.5, 0.0, 505.0, 241.0, 0.0, 0.0, 1.0;
  c.distortion = {-0.25, 0.08, 0.001, -0.0015, -0.01};
  return c;
}

// Brown-Conrady as OpenCV documents it, written out independently, in our pixel convention
// (centres at +0.5): where the lens puts the point that a pinhole would put at `pixel`.
Eigen::Vector2d DistortByHand(const CameraCalibration& c, const Eigen::Vector2d& pixel) {
  const Eigen::Matrix3d& k = c.camera_matrix;
  const double x = (pixel.x() - 0.5 - k(0, 2)) / k(0, 0);
  const double y = (pixel.y() - 0.5 - k(1, 2)) / k(1, 1);
  const double k1 = c.distortion[0], k2 = c.distortion[1], p1 = c.distortion[2],
               p2 = c.distortion[3], k3 = c.distortion[4];
  const double r2 = x * x + y * y;
  const double radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2;
  const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
  const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
  return {k(0, 0) * xd + k(0, 2) + 0.5, k(1, 1) * yd + k(1, 2) + 0.5};
}

TEST(UndistorterTest, PointsGoThroughTheLensModelAndBack) {
  const CameraCalibration lens = Lens();
  const Undistorter undistorter(lens);
  for (const Eigen::Vector2d& pixel :
       {Eigen::Vector2d(320.0, 241.5), Eigen::Vector2d(60.0, 50.0), Eigen::Vector2d(600.0, 420.0),
        Eigen::Vector2d(100.25, 400.75)}) {
    const Eigen::Vector2d distorted = undistorter.DistortPixel(pixel);
    EXPECT_LT((distorted - DistortByHand(lens, pixel)).norm(), 1e-9) << pixel.transpose();
    EXPECT_LT((undistorter.UndistortPixel(distorted) - pixel).norm(), 1e-4) << pixel.transpose();
  }
  // The principal point does not move; a corner moves by tens of pixels.
  EXPECT_LT((undistorter.DistortPixel({320.0, 241.5}) - Eigen::Vector2d(320.0, 241.5)).norm(),
            1e-9);
  EXPECT_GT((undistorter.DistortPixel({60.0, 50.0}) - Eigen::Vector2d(60.0, 50.0)).norm(), 20.0);
}

// The centroid of a bright spot, over pixels brighter than `threshold`, in our convention.
Eigen::Vector2d SpotCentroid(const RgbImage& image, int threshold) {
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      const double v = image.Pixel(r, c)[1];
      if (v < threshold) continue;
      sum += v;
      sx += v * (c + 0.5);
      sy += v * (r + 0.5);
    }
  }
  return {sx / sum, sy / sum};
}

TEST(UndistorterTest, MovesADistortedSpotBackToWhereAPinholeWouldSeeIt) {
  const CameraCalibration lens = Lens();
  const Undistorter undistorter(lens);
  const Eigen::Vector2d truth(110.5, 95.25);  // where a pinhole camera would see the spot
  const Eigen::Vector2d seen = DistortByHand(lens, truth);
  ASSERT_GT((seen - truth).norm(), 10.0);  // far enough that a no-op would fail
  RgbImage raw;
  raw.width = lens.image_width;
  raw.height = lens.image_height;
  raw.rgb.assign(static_cast<size_t>(raw.width) * raw.height * 3, 0);
  const double sigma_px = 2.0;
  for (int r = 0; r < raw.height; ++r) {
    for (int c = 0; c < raw.width; ++c) {
      const double d2 = std::pow(c + 0.5 - seen.x(), 2) + std::pow(r + 0.5 - seen.y(), 2);
      const uint8_t v =
          static_cast<uint8_t>(std::lround(250.0 * std::exp(-d2 / (2 * sigma_px * sigma_px))));
      uint8_t* p = raw.rgb.data() + (static_cast<size_t>(r) * raw.width + c) * 3;
      p[0] = 0;
      p[1] = v;
      p[2] = 0;
    }
  }
  EXPECT_LT((SpotCentroid(raw, 20) - seen).norm(), 0.05);
  const RgbImage fixed = undistorter.Apply(raw);
  ASSERT_EQ(fixed.width, 640);
  ASSERT_EQ(fixed.height, 480);
  const Eigen::Vector2d centroid = SpotCentroid(fixed, 20);
  EXPECT_LT((centroid - truth).norm(), 0.2) << centroid.transpose() << " vs " << truth.transpose();
  // The channels stay where they were.
  double red = 0.0;
  for (size_t i = 0; i < fixed.rgb.size(); i += 3) red += fixed.rgb[i];
  EXPECT_EQ(red, 0.0);
}

TEST(UndistorterTest, RejectsAFrameOfAnotherSize) {
  const Undistorter undistorter(Lens());
  RgbImage small;
  small.width = 320;
  small.height = 240;
  small.rgb.assign(320 * 240 * 3, 0);
  try {
    undistorter.Apply(small);
    ADD_FAILURE() << "no UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(),
                ::testing::HasSubstr("320x240 frame with a calibration made for 640x480"));
  }
}

}  // namespace
}  // namespace recon::camera
