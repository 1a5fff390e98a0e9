#include "devices/camera/opencv_camera.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "devices/camera/open_camera.h"
#include "engine/core/error.h"
#include "tests/devices/camera/camera_test_files.h"

namespace recon::camera {
namespace {

using testing::BarIndex;
using ::testing::HasSubstr;
using testing::ScratchDir;

// Expects `body` to throw UserError whose message contains every one of `parts`.
template <typename Body>
void ExpectUserError(Body body, std::initializer_list<std::string> parts) {
  try {
    body();
    ADD_FAILURE() << "no UserError";
  } catch (const UserError& e) {
    for (const std::string& part : parts) EXPECT_THAT(e.what(), HasSubstr(part));
  }
}

TEST(OpenCvCameraTest, ReadsAnMjpgFileBackInOrderWithItsTimestamps) {
  ScratchDir dir;
  const std::string video = dir / "bars.avi";
  testing::WriteBarVideo(video, 8, 10.0);
  OpenCvCamera camera(video);
  EXPECT_FALSE(camera.is_live());
  EXPECT_EQ(camera.width(), testing::kBarFrameWidth);
  EXPECT_EQ(camera.height(), testing::kBarFrameHeight);
  EXPECT_DOUBLE_EQ(camera.nominal_fps(), 10.0);
  EXPECT_THAT(camera.Describe(), HasSubstr("160x120 at 10 fps"));
  EXPECT_THAT(camera.Describe(), HasSubstr(video));
  for (int i = 0; i < 8; ++i) {
    const devices::CameraFrame frame = camera.Capture();
    ASSERT_EQ(frame.image.width, testing::kBarFrameWidth);
    ASSERT_EQ(frame.image.rgb.size(), size_t{160 * 120 * 3});
    // A red bar read back as red (not blue) also checks the BGR to RGB conversion.
    EXPECT_EQ(BarIndex(frame.image), i) << "frame " << i;
    EXPECT_EQ(frame.sequence, i);
    EXPECT_NEAR(frame.timestamp_s, 0.1 * i, 1e-6);
  }
  EXPECT_EQ(camera.frames(), 8);
  ExpectUserError([&] { camera.Capture(); }, {"video file", video, "ended after 8 frames"});
}

TEST(OpenCvCameraTest, LoopsAFileWithTimestampsThatKeepIncreasing) {
  ScratchDir dir;
  const std::string video = dir / "bars.avi";
  testing::WriteBarVideo(video, 5, 20.0);
  OpenCvCameraOptions options;
  options.loop = true;
  OpenCvCamera camera(video, options);
  for (int i = 0; i < 12; ++i) {
    const devices::CameraFrame frame = camera.Capture();
    EXPECT_EQ(BarIndex(frame.image), i % 5) << "frame " << i;
    EXPECT_EQ(frame.sequence, i);
    EXPECT_NEAR(frame.timestamp_s, 0.05 * i, 1e-6) << "frame " << i;
  }
}

TEST(OpenCvCameraTest, AMissingOrUnreadableSourceIsAUserErrorNamingIt) {
  // No /dev/video* on the test machines: the V4L2 path can only be tested for its errors.
  ExpectUserError([] { OpenCvCamera camera("/dev/video-recon-missing"); },
                  {"camera /dev/video-recon-missing", "no such device"});
  ExpectUserError([] { OpenCvCamera camera("/dev/null"); }, {"cannot open the camera /dev/null"});
  ExpectUserError([] { OpenCvCamera camera("97"); }, {"cannot open the camera 97"});
  ExpectUserError([] { OpenCvCamera camera("/nonexistent/clip.avi"); },
                  {"video file /nonexistent/clip.avi", "no such file"});
  ScratchDir dir;
  const std::string garbage = dir / "garbage.avi";
  std::ofstream(garbage) << "this is not a video\n";
  ExpectUserError([&] { OpenCvCamera camera(garbage); }, {garbage});
}

TEST(OpenCvCameraTest, RejectsACalibrationForAnotherFrameSize) {
  ScratchDir dir;
  const std::string video = dir / "bars.avi";
  testing::WriteBarVideo(video, 2, 10.0);
  OpenCvCameraOptions options;
  options.undistort =
      CameraCalibration::FromIntrinsics(tags::CameraIntrinsics::FromFovy(60, 640, 480));
  ExpectUserError([&] { OpenCvCamera camera(video, options); }, {"640x480", "160x120", video});
}

TEST(OpenCameraTest, TellsDevicesFilesAndFoldersApart) {
  ScratchDir dir;
  EXPECT_EQ(ClassifyCameraSource("/dev/video0"), CameraSourceKind::kV4l2Device);
  EXPECT_EQ(ClassifyCameraSource("2"), CameraSourceKind::kV4l2Device);
  EXPECT_EQ(ClassifyCameraSource(dir.path().string()), CameraSourceKind::kImageSequence);
  EXPECT_EQ(ClassifyCameraSource(dir / "clip.mp4"), CameraSourceKind::kVideoFile);
  const std::string video = dir / "bars.avi";
  testing::WriteBarVideo(video, 3, 10.0);
  const std::unique_ptr<devices::Camera> camera = OpenCamera(video);
  EXPECT_EQ(BarIndex(camera->Capture().image), 0);
  EXPECT_EQ(BarIndex(camera->Capture().image), 1);
}

}  // namespace
}  // namespace recon::camera
