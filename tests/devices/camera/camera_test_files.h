#pragma once

// Files the camera tests write and read back: a scratch folder per test and frames whose index
// is visible in their pixels (a coloured bar), so a reader's order and content can be checked
// through lossy JPEG.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "engine/core/image.h"

namespace recon::camera::testing {

/// A fresh folder under the gtest temp dir named after the running test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::path(::testing::TempDir()) /
            ("recon-camera-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
             std::to_string(getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

constexpr int kBarFrameWidth = 160;
constexpr int kBarFrameHeight = 120;
constexpr int kBars = 8;
constexpr int kBarWidth = kBarFrameWidth / kBars;

/// A BGR frame: dark grey with a red bar (RGB 220, 30, 30) in column block `index % kBars`.
inline cv::Mat BarFrame(int index) {
  cv::Mat frame(kBarFrameHeight, kBarFrameWidth, CV_8UC3, cv::Scalar(40, 40, 40));
  cv::rectangle(frame, cv::Rect((index % kBars) * kBarWidth, 0, kBarWidth, kBarFrameHeight),
                cv::Scalar(30, 30, 220), cv::FILLED);
  return frame;
}

/// Which column block of an RGB frame holds the red bar (-1: none, or not clearly one). The
/// mean over the middle of each block is taken, so JPEG ringing at the edges does not matter.
inline int BarIndex(const RgbImage& image) {
  int found = -1;
  for (int b = 0; b < kBars; ++b) {
    double r = 0.0, g = 0.0, blue = 0.0;
    int n = 0;
    for (int row = 10; row < image.height - 10; ++row) {
      for (int col = b * kBarWidth + 5; col < (b + 1) * kBarWidth - 5; ++col) {
        const uint8_t* p = image.Pixel(row, col);
        r += p[0];
        g += p[1];
        blue += p[2];
        ++n;
      }
    }
    r /= n;
    g /= n;
    blue /= n;
    if (r > 180 && g < 70 && blue < 70) {
      if (found >= 0) return -1;
      found = b;
    } else if (r > 70) {
      return -1;  // neither the bar nor the grey background
    }
  }
  return found;
}

/// Writes `count` BarFrames as an MJPG .avi with OpenCV's own encoder (no ffmpeg needed).
inline void WriteBarVideo(const std::string& path, int count, double fps) {
  cv::VideoWriter writer(path, cv::CAP_OPENCV_MJPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                         fps, cv::Size(kBarFrameWidth, kBarFrameHeight));
  ASSERT_TRUE(writer.isOpened()) << path;
  for (int i = 0; i < count; ++i) writer.write(BarFrame(i));
}

}  // namespace recon::camera::testing
