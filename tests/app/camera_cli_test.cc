// `recon camera info|grab|pose` on files a user could have: an MJPG .avi, a folder of PNG frames,
// an OpenCV calibration YAML and a table tags JSON. This machine has no /dev/video*, so live
// devices are tested for their errors only.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/image_file.h"
#include "devices/camera/opencv_image.h"
#include "devices/camera/table_tags_file.h"
#include "tests/app/run_recon.h"
#include "tests/devices/camera/camera_test_files.h"
#include "tests/tags/synthetic_scene.h"

namespace recon {
namespace {

std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using camera::testing::BarIndex;
using camera::testing::ScratchDir;
using ::testing::HasSubstr;

camera::CameraCalibration BarCalibration(std::vector<double> distortion = {}) {
  camera::CameraCalibration c;
  c.image_width = camera::testing::kBarFrameWidth;
  c.image_height = camera::testing::kBarFrameHeight;
  c.camera_matrix << 150.0, 0.0, 79.5, 0.0, 150.0, 59.5, 0.0, 0.0, 1.0;
  c.distortion = std::move(distortion);
  return c;
}

nlohmann::json ParseJson(const std::string& output) {
  const size_t start = output.find('{');
  EXPECT_NE(start, std::string::npos) << output;
  return nlohmann::json::parse(output.substr(start));
}

TEST(CameraCliTest, InfoOnAVideoFileGivesSizeRateBackendAndIntrinsics) {
  ScratchDir dir;
  camera::testing::WriteBarVideo(dir / "bars.avi", 40, 15.0);
  camera::WriteCameraCalibration(dir / "cam.yaml", BarCalibration({-0.1, 0.01, 0, 0, 0}));
  const testing::CommandResult r =
      testing::RunRecon("camera info --device " + (dir / "bars.avi") + " --calibration " +
                        (dir / "cam.yaml") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json info = ParseJson(r.output);
  EXPECT_EQ(info["width"], 160);
  EXPECT_EQ(info["height"], 120);
  EXPECT_EQ(info["frames"], 30);
  EXPECT_NEAR(info["measured_fps"].get<double>(), 15.0, 1e-3);
  EXPECT_FALSE(info["backend"].get<std::string>().empty());
  EXPECT_EQ(info["failed_reads"], 0);
  // Our convention: OpenCV's 79.5 is 80.0 with pixel centres at +0.5.
  EXPECT_DOUBLE_EQ(info["intrinsics"]["cx"].get<double>(), 80.0);
  EXPECT_DOUBLE_EQ(info["intrinsics"]["fy"].get<double>(), 150.0);
  EXPECT_DOUBLE_EQ(info["intrinsics"]["distortion"][0].get<double>(), -0.1);

  const testing::CommandResult text =
      testing::RunRecon("camera info --device " + (dir / "bars.avi"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_THAT(text.output, HasSubstr("160x120"));
  EXPECT_THAT(text.output, HasSubstr("15.00 fps measured"));
}

// OpenCV's video and image-file libraries are loaded only by what reads a camera or an image
// (opencv_io.h): with the module unreachable, help still runs and reading a video file stops with
// an error that names the module's path.
TEST(CameraCliTest, OpenCvIoIsLoadedOnlyByWhatNeedsIt) {
  ScratchDir dir;
  camera::testing::WriteBarVideo(dir / "bars.avi", 5, 15.0);
  const std::string missing = dir / "librecon_opencv_io.so";
  const std::string env = "RECON_OPENCV_IO_MODULE=" + missing + " ";
  const testing::CommandResult help = testing::RunCommand(env + RECON_CLI + " --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  const testing::CommandResult info =
      testing::RunCommand(env + RECON_CLI + " camera info --device " + (dir / "bars.avi"));
  EXPECT_EQ(info.exit_code, 2) << info.output;
  EXPECT_THAT(info.output, HasSubstr("cannot load the OpenCV I/O module " + missing));
  EXPECT_THAT(info.output, HasSubstr("cameras and image files need it"));
}

TEST(CameraCliTest, GrabSavesNumberedFramesFromAFolderAndUndistorts) {
  ScratchDir dir;
  std::filesystem::create_directories(dir / "frames");
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(
        cv::imwrite(dir / ("frames/f" + std::to_string(i) + ".png"), camera::testing::BarFrame(i)));
  }
  testing::CommandResult r = testing::RunRecon("camera grab --device " + (dir / "frames") +
                                               " --out " + (dir / "out.png") + " --count 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (int i = 0; i < 3; ++i) {
    const std::string path = dir / ("out_000" + std::to_string(i) + ".png");
    const cv::Mat saved = cv::imread(path);
    ASSERT_FALSE(saved.empty()) << path;
    EXPECT_EQ(BarIndex(camera::RgbFromMat(saved, path)), i);
  }
  // Grabbing again over the saved frames needs --force; without it nothing is touched.
  const std::string first = ReadFileBytes(dir / "out_0000.png");
  r = testing::RunRecon("camera grab --device " + (dir / "frames") + " --out " + (dir / "out.png") +
                        " --count 3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("out_0000.png already exists"));
  EXPECT_EQ(ReadFileBytes(dir / "out_0000.png"), first);
  r = testing::RunRecon("camera grab --device " + (dir / "frames") + " --out " + (dir / "out.png") +
                        " --count 3 --force");
  EXPECT_EQ(r.exit_code, 0) << r.output;

  camera::WriteCameraCalibration(dir / "cam.yaml", BarCalibration({-0.4, 0.1, 0, 0, 0}));
  r = testing::RunRecon("camera grab --device " + (dir / "frames") + " --out " +
                        (dir / "flat.png") + " --undistort --calibration " + (dir / "cam.yaml"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const cv::Mat raw = cv::imread(dir / "out_0000.png");
  const cv::Mat flat = cv::imread(dir / "flat.png");
  ASSERT_EQ(flat.size(), raw.size());
  EXPECT_GT(cv::norm(raw, flat, cv::NORM_L1), 1000.0);  // barrel distortion removed: it changed

  r = testing::RunRecon("camera grab --device " + (dir / "frames") + " --out " + (dir / "x.png") +
                        " --undistort");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--undistort needs --calibration"));
}

TEST(CameraCliTest, BadDevicesAndFilesExitTwoNamingThem) {
  ScratchDir dir;
  testing::CommandResult r = testing::RunRecon("camera info --device /dev/video-recon-missing");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("camera /dev/video-recon-missing"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("WARN")));  // OpenCV's own log is silenced

  r = testing::RunRecon("camera grab --device " + (dir / "none.avi") + " --out " + (dir / "a.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("video file " + (dir / "none.avi") + ": no such file"));

  r = testing::RunRecon("camera info --device " + dir.path().string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr(dir.path().string() + " holds no .png or .jpg frames"));

  camera::testing::WriteBarVideo(dir / "bars.avi", 5, 10.0);
  r = testing::RunRecon("camera info --device " + (dir / "bars.avi"));
  EXPECT_EQ(r.exit_code, 2);  // 30 frames asked of a 5-frame file
  EXPECT_THAT(r.output, HasSubstr("ended after 5 frames"));

  std::ofstream(dir / "bad.yaml") << "%YAML:1.0\nimage_width: 160\nimage_height: 120\n";
  r = testing::RunRecon("camera info --device " + (dir / "bars.avi") +
                        " --frames 2 --calibration " + (dir / "bad.yaml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr((dir / "bad.yaml") + ": key 'camera_matrix' is missing"));

  camera::CameraCalibration other = BarCalibration();
  other.image_width = 640;
  camera::WriteCameraCalibration(dir / "other.yaml", other);
  r = testing::RunRecon("camera info --device " + (dir / "bars.avi") +
                        " --frames 2 --calibration " + (dir / "other.yaml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("is for 640x120 frames but"));
}

TEST(CameraCliTest, PoseFindsTheCameraFromTableTagsInAFrame) {
  ScratchDir dir;
  tags::testing::SceneCamera scene_camera;  // 1 m above the table origin, looking down
  scene_camera.position_m = {0.02, -0.03, 1.0};
  const std::vector<camera::TableTag> table_tags = {{0, {-0.45, -0.3, 0.0}, 0.08, 0.0},
                                                    {1, {0.45, -0.3, 0.0}, 0.08, 0.0},
                                                    {2, {0.45, 0.3, 0.0}, 0.08, 0.0},
                                                    {3, {-0.45, 0.3, 0.0}, 0.08, 0.0}};
  std::vector<tags::testing::PlacedTag> placed;
  for (const auto& t : table_tags) placed.push_back({t.id, t.center_table_m, t.yaw_rad, t.size_m});
  std::filesystem::create_directories(dir / "frames");
  camera::WriteImage(dir / "frames/0.png",
                     tags::testing::RenderScene(scene_camera, placed, {}, {}));
  camera::WriteTableTags(dir / "tags.json", table_tags);
  camera::WriteCameraCalibration(
      dir / "cam.yaml",
      camera::CameraCalibration::FromIntrinsics(tags::CameraIntrinsics::FromFovy(60.0, 640, 480)));
  const testing::CommandResult r =
      testing::RunRecon("camera pose --device " + (dir / "frames") + " --calibration " +
                        (dir / "cam.yaml") + " --tags " + (dir / "tags.json") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json pose = ParseJson(r.output);
  const auto p = pose["position_table_m"].get<std::vector<double>>();
  EXPECT_NEAR(p[0], 0.02, 0.003);
  EXPECT_NEAR(p[1], -0.03, 0.003);
  EXPECT_NEAR(p[2], 1.0, 0.003);
  EXPECT_LT(pose["reprojection_rms_px"].get<double>(), 0.3);
  EXPECT_EQ(pose["used_ids"].size(), 4u);

  const testing::CommandResult bad =
      testing::RunRecon("camera pose --device " + (dir / "frames") + " --calibration " +
                        (dir / "cam.yaml") + " --tags " + (dir / "cam.yaml"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr((dir / "cam.yaml") + ": not valid JSON"));
}

}  // namespace
}  // namespace recon
