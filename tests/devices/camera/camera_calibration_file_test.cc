#include "devices/camera/camera_calibration_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>

#include "engine/core/error.h"
#include "tests/devices/camera/camera_test_files.h"

namespace recon::camera {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::ScratchDir;

// What OpenCV's calibration sample (samples/cpp/calibration.cpp) writes, trimmed.
constexpr char kOpenCvSample[] = R"(%YAML:1.0
---
calibration_time: "Mon 01 Jan 2024 10:00:00 CET"
nr_of_frames: 25
image_width: 640
image_height: 480
board_width: 9
board_height: 6
square_size: 2.5000000372529030e-02
flags: 0
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 6.0012e+02, 0., 3.1950e+02, 0., 6.0521e+02, 2.4150e+02, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 5
   cols: 1
   dt: d
   data: [ -2.1e-01, 5.5e-02, 1.0e-03, -2.0e-03, 0. ]
avg_reprojection_error: 2.1e-01
)";

std::string Write(const ScratchDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

std::string CalibrationError(const std::string& path) {
  try {
    ReadCameraCalibration(path);
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no UserError)";
}

// The sample with `from` replaced by `to`.
std::string Edited(const std::string& from, const std::string& to) {
  std::string text = kOpenCvSample;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(CameraCalibrationFileTest, ReadsWhatOpenCvsCalibrationSampleWrites) {
  ScratchDir dir;
  const CameraCalibration c = ReadCameraCalibration(Write(dir, "cam.yaml", kOpenCvSample));
  EXPECT_EQ(c.image_width, 640);
  EXPECT_EQ(c.image_height, 480);
  EXPECT_DOUBLE_EQ(c.camera_matrix(0, 0), 600.12);
  EXPECT_DOUBLE_EQ(c.camera_matrix(1, 1), 605.21);
  EXPECT_DOUBLE_EQ(c.camera_matrix(0, 2), 319.5);
  EXPECT_DOUBLE_EQ(c.camera_matrix(1, 2), 241.5);
  EXPECT_THAT(c.distortion, ElementsAre(-0.21, 0.055, 0.001, -0.002, 0.0));
  EXPECT_FALSE(c.HasNoDistortion());
  // OpenCV's principal point at pixel (319.5, 241.5) with centres on integers is (320, 242) in
  // ours, where pixel centres sit at +0.5.
  const tags::CameraIntrinsics k = c.ToIntrinsics();
  EXPECT_DOUBLE_EQ(k.cx, 320.0);
  EXPECT_DOUBLE_EQ(k.cy, 242.0);
  EXPECT_DOUBLE_EQ(k.fx, 600.12);
  EXPECT_EQ(k.width, 640);
}

TEST(CameraCalibrationFileTest, RoundTripsAndOpenCvReadsWhatItWrites) {
  ScratchDir dir;
  for (const size_t count : {0u, 4u, 5u, 8u, 12u, 14u}) {
    CameraCalibration c;
    c.image_width = 1280;
    c.image_height = 720;
    c.camera_matrix << 910.25, 0.0, 641.75, 0.0, 905.5, 359.125, 0.0, 0.0, 1.0;
    for (size_t i = 0; i < count; ++i) c.distortion.push_back(0.01 * (i + 1) * (i % 2 ? -1 : 1));
    const std::string path = dir / ("cal" + std::to_string(count) + ".yaml");
    WriteCameraCalibration(path, c);
    const CameraCalibration back = ReadCameraCalibration(path);
    EXPECT_EQ(back.image_width, 1280);
    EXPECT_EQ(back.image_height, 720);
    EXPECT_EQ(back.camera_matrix, c.camera_matrix);
    // None is written as OpenCV's five zeros.
    EXPECT_EQ(back.distortion, count == 0 ? std::vector<double>(5, 0.0) : c.distortion);

    cv::FileStorage fs(path, cv::FileStorage::READ);
    cv::Mat k, d;
    fs["camera_matrix"] >> k;
    fs["distortion_coefficients"] >> d;
    ASSERT_EQ(k.rows, 3);
    ASSERT_EQ(k.cols, 3);
    EXPECT_DOUBLE_EQ(k.at<double>(0, 2), 641.75);
    EXPECT_EQ(d.total(), count == 0 ? 5u : count);
    EXPECT_EQ(static_cast<int>(fs["image_width"]), 1280);
  }
}

TEST(CameraCalibrationFileTest, IntrinsicsConvertBothWays) {
  const tags::CameraIntrinsics k = tags::CameraIntrinsics::FromFovy(60.0, 640, 480);
  const CameraCalibration c = CameraCalibration::FromIntrinsics(k);
  EXPECT_DOUBLE_EQ(c.camera_matrix(0, 2), 319.5);
  EXPECT_DOUBLE_EQ(c.camera_matrix(1, 2), 239.5);
  EXPECT_TRUE(c.HasNoDistortion());
  const tags::CameraIntrinsics back = c.ToIntrinsics();
  EXPECT_DOUBLE_EQ(back.cx, k.cx);
  EXPECT_DOUBLE_EQ(back.cy, k.cy);
  EXPECT_DOUBLE_EQ(back.fy, k.fy);
  EXPECT_EQ(back.height, 480);
}

TEST(CameraCalibrationFileTest, AcceptsRosStyleMatricesWithoutTheOpenCvTag) {
  ScratchDir dir;
  const std::string path = Write(dir, "ros.yaml", R"(image_width: 640
image_height: 480
camera_name: top
camera_matrix:
  rows: 3
  cols: 3
  data: [500.0, 0.0, 320.0, 0.0, 500.0, 240.0, 0.0, 0.0, 1.0]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0.1, -0.05, 0.0, 0.0, 0.0]
)");
  const CameraCalibration c = ReadCameraCalibration(path);
  EXPECT_DOUBLE_EQ(c.camera_matrix(0, 0), 500.0);
  EXPECT_THAT(c.distortion, ElementsAre(0.1, -0.05, 0.0, 0.0, 0.0));
}

TEST(CameraCalibrationFileTest, BadFilesNameTheFileAndTheKey) {
  ScratchDir dir;
  std::string path =
      Write(dir, "no_dist.yaml", Edited("distortion_coefficients:", "other_coefficients:"));
  EXPECT_THAT(CalibrationError(path),
              HasSubstr(path + ": key 'distortion_coefficients' is missing"));

  path = Write(dir, "no_width.yaml", Edited("image_width: 640", "width: 640"));
  EXPECT_THAT(CalibrationError(path), HasSubstr(path + ": key 'image_width' is missing"));

  path = Write(dir, "neg_height.yaml", Edited("image_height: 480", "image_height: -480"));
  EXPECT_THAT(CalibrationError(path), HasSubstr("key 'image_height' must be a positive integer"));

  path = Write(dir, "k2x2.yaml",
               Edited("rows: 3\n   cols: 3\n   dt: d\n   data: [ 6.0012e+02, 0., 3.1950e+02, 0., "
                      "6.0521e+02, 2.4150e+02, 0., 0., 1. ]",
                      "rows: 2\n   cols: 2\n   dt: d\n   data: [ 600., 0., 0., 600. ]"));
  EXPECT_THAT(CalibrationError(path),
              HasSubstr(path + ": key 'camera_matrix' is 2x2, expected 3x3"));

  path = Write(dir, "short_data.yaml", Edited("0., 0., 1. ]", "0., 0. ]"));
  EXPECT_THAT(CalibrationError(path),
              HasSubstr("key 'camera_matrix' holds 8 values for a 3x3 matrix"));

  path =
      Write(dir, "scalar.yaml", Edited("camera_matrix: !!opencv-matrix", "camera_matrix: 3\nx:"));
  EXPECT_THAT(CalibrationError(path), HasSubstr("key 'camera_matrix' is not a matrix"));

  path = Write(dir, "six.yaml",
               Edited("rows: 5\n   cols: 1\n   dt: d\n   data: [ -2.1e-01, 5.5e-02, 1.0e-03, "
                      "-2.0e-03, 0. ]",
                      "rows: 6\n   cols: 1\n   dt: d\n   data: [ 0., 0., 0., 0., 0., 0. ]"));
  EXPECT_THAT(CalibrationError(path),
              HasSubstr("'distortion_coefficients' has 6 values; OpenCV knows"));

  path = Write(dir, "garbage.yaml", "\x01\x02 {{{ [ not: yaml: at all\n\t- ]]\n");
  EXPECT_THAT(CalibrationError(path), HasSubstr(path));

  path = Write(dir, "empty.yaml", "");
  EXPECT_THAT(CalibrationError(path), HasSubstr(path));

  EXPECT_THAT(CalibrationError(dir / "missing.yaml"), HasSubstr("missing.yaml: no such file"));
}

TEST(CameraCalibrationFileTest, RefusesToWriteAnInvalidCalibration) {
  ScratchDir dir;
  CameraCalibration c;  // no size
  EXPECT_THROW(WriteCameraCalibration(dir / "bad.yaml", c), UserError);
  c.image_width = 10;
  c.image_height = 10;
  c.camera_matrix(0, 0) = 0.0;
  EXPECT_THROW(WriteCameraCalibration(dir / "bad.yaml", c), UserError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.yaml"));
}

}  // namespace
}  // namespace recon::camera
