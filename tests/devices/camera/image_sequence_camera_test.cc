#include "devices/camera/image_sequence_camera.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "engine/core/error.h"
#include "tests/devices/camera/camera_test_files.h"

namespace recon::camera {
namespace {

using testing::BarIndex;
using ::testing::HasSubstr;
using testing::ScratchDir;

std::string UserErrorOf(const std::function<void()>& body) {
  try {
    body();
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no UserError)";
}

// Writes frames out of name order, mixing PNG and JPG and a non-image file that is skipped.
void WriteFrames(const ScratchDir& dir) {
  ASSERT_TRUE(cv::imwrite(dir / "frame_002.png", testing::BarFrame(2)));
  ASSERT_TRUE(cv::imwrite(dir / "frame_000.jpg", testing::BarFrame(0)));
  ASSERT_TRUE(cv::imwrite(dir / "frame_001.PNG", testing::BarFrame(1)));
  ASSERT_TRUE(cv::imwrite(dir / "frame_003.jpeg", testing::BarFrame(3)));
  std::ofstream(dir / "notes.txt") << "not a frame\n";
}

TEST(ImageSequenceCameraTest, ServesFramesInNameOrderAtTheGivenRate) {
  ScratchDir dir;
  WriteFrames(dir);
  ImageSequenceOptions options;
  options.fps = 4.0;
  ImageSequenceCamera camera(dir.path().string(), options);
  ASSERT_EQ(camera.files().size(), 4u);
  EXPECT_EQ(camera.width(), testing::kBarFrameWidth);
  EXPECT_THAT(camera.Describe(), HasSubstr("(4 frames), 160x120 at 4 fps"));
  for (int i = 0; i < 4; ++i) {
    const devices::CameraFrame frame = camera.Capture();
    EXPECT_EQ(BarIndex(frame.image), i);
    EXPECT_EQ(frame.sequence, i);
    EXPECT_DOUBLE_EQ(frame.timestamp_s, i / 4.0);
  }
  EXPECT_THAT(UserErrorOf([&] { camera.Capture(); }),
              HasSubstr("image sequence " + dir.path().string() + " ended after 4 frames"));
}

TEST(ImageSequenceCameraTest, LoopsWithIncreasingTimestamps) {
  ScratchDir dir;
  WriteFrames(dir);
  ImageSequenceOptions options;
  options.fps = 10.0;
  options.loop = true;
  ImageSequenceCamera camera(dir.path().string(), options);
  for (int i = 0; i < 10; ++i) {
    const devices::CameraFrame frame = camera.Capture();
    EXPECT_EQ(BarIndex(frame.image), i % 4);
    EXPECT_EQ(frame.sequence, i);
    EXPECT_DOUBLE_EQ(frame.timestamp_s, i / 10.0);
  }
}

TEST(ImageSequenceCameraTest, RealTimePacingKeepsTheNominalTimestamps) {
  ScratchDir dir;
  WriteFrames(dir);
  ImageSequenceOptions options;
  options.fps = 200.0;
  options.real_time = true;
  ImageSequenceCamera camera(dir.path().string(), options);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(camera.Capture().timestamp_s, i / 200.0);
}

TEST(ImageSequenceCameraTest, EmptyMissingOrUnreadableFramesAreUserErrors) {
  ScratchDir dir;
  EXPECT_THAT(UserErrorOf([&] { ImageSequenceCamera camera(dir.path().string()); }),
              HasSubstr(dir.path().string() + " holds no .png or .jpg frames"));
  EXPECT_THAT(UserErrorOf([&] { ImageSequenceCamera camera(dir / "missing"); }),
              HasSubstr("not a folder"));
  ASSERT_TRUE(cv::imwrite(dir / "a.png", testing::BarFrame(0)));
  std::ofstream(dir / "b.png") << "truncated";
  ImageSequenceCamera camera(dir.path().string());
  EXPECT_EQ(BarIndex(camera.Capture().image), 0);
  EXPECT_THAT(UserErrorOf([&] { camera.Capture(); }),
              HasSubstr("cannot read the frame " + (dir / "b.png")));
  // An unreadable first frame is found when the camera is made.
  std::filesystem::remove(dir / "a.png");
  EXPECT_THAT(UserErrorOf([&] { ImageSequenceCamera again(dir.path().string()); }),
              HasSubstr(dir / "b.png"));
}

TEST(ImageSequenceCameraTest, AFrameOfAnotherSizeIsAUserErrorNamingIt) {
  ScratchDir dir;
  ASSERT_TRUE(cv::imwrite(dir / "a.png", testing::BarFrame(0)));
  ASSERT_TRUE(cv::imwrite(dir / "b.png", cv::Mat(10, 10, CV_8UC3, cv::Scalar(0, 0, 0))));
  ImageSequenceCamera camera(dir.path().string());
  camera.Capture();
  EXPECT_THAT(UserErrorOf([&] { camera.Capture(); }), HasSubstr((dir / "b.png") + " is 10x10"));
}

}  // namespace
}  // namespace recon::camera
