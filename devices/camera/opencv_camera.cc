#include "devices/camera/opencv_camera.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/videoio.hpp>  // the CAP_ constants only: the calls go through opencv_io.h

#include "devices/camera/opencv_image.h"
#include "devices/camera/opencv_io.h"
#include "devices/camera/undistorter.h"
#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::camera {

struct OpenCvCamera::State {
  std::unique_ptr<VideoCaptureIo> capture = LoadOpenCvIo().new_capture();
  cv::Mat bgr;
  std::optional<devices::CameraFrame> pending;  // the first frame, read while opening
  std::optional<Undistorter> undistorter;
};

namespace {

bool IsIndex(const std::string& device) {
  if (device.empty() || device.size() > 4) return false;
  for (char c : device) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// cv::VideoWriter::fourcc, which would need videoio linked: the code's four bytes, first lowest.
double FourCc(const std::string& code) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i)
    value = (value << 8) | static_cast<uint8_t>(code[static_cast<size_t>(i)]);
  return static_cast<double>(value);
}

std::string FormatFps(double fps) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", fps);
  return text;
}

}  // namespace

OpenCvCamera::OpenCvCamera(const std::string& device, OpenCvCameraOptions options)
    : device_(device), options_(std::move(options)), state_(std::make_unique<State>()) {
  live_ = IsIndex(device) || device.rfind("/dev/", 0) == 0;
  const std::string what = (live_ ? "camera " : "video file ") + device;
  if (options_.max_consecutive_failures < 1) {
    throw UserError("the number of failed reads before giving up must be at least 1");
  }
  if (!live_ && !std::filesystem::is_regular_file(device)) {
    throw UserError("cannot open the " + what + ": no such file");
  }
  if (device.rfind("/dev/", 0) == 0 && !std::filesystem::exists(device)) {
    throw UserError("cannot open the " + what + ": no such device (is it plugged in?)");
  }
  VideoCaptureIo& capture = *state_->capture;
  try {
    if (IsIndex(device)) {
      capture.OpenIndex(std::stoi(device), cv::CAP_V4L2);
    } else if (live_) {
      capture.Open(device, cv::CAP_V4L2);
    } else {
      // FFmpeg reads nearly every file; OpenCV's own MJPEG reader is the fallback for .avi
      // files where FFmpeg is missing. CAP_ANY would also try GStreamer and image patterns,
      // which only add noise on stderr for a file neither can read.
      if (!capture.Open(device, cv::CAP_FFMPEG)) capture.Open(device, cv::CAP_OPENCV_MJPEG);
    }
  } catch (const cv::Exception& e) {
    throw UserError("cannot open the " + what + ": " + e.err);
  }
  if (!capture.IsOpened()) {
    throw UserError("cannot open the " + what +
                    (live_ ? ": it is not a V4L2 capture device or is busy"
                           : ": OpenCV has no backend that can read it"));
  }
  backend_ = capture.BackendName();
  if (live_) {
    // Each request is a hint: the driver keeps the nearest mode it has; what it chose is read
    // back below from the first frame and CAP_PROP_FPS.
    if (options_.fourcc.size() == 4) {
      const std::string& f = options_.fourcc;
      capture.Set(cv::CAP_PROP_FOURCC, FourCc(f));
    } else if (!options_.fourcc.empty()) {
      throw UserError("the pixel format '" + options_.fourcc + "' is not a four-letter code");
    }
    if (options_.width > 0) capture.Set(cv::CAP_PROP_FRAME_WIDTH, options_.width);
    if (options_.height > 0) capture.Set(cv::CAP_PROP_FRAME_HEIGHT, options_.height);
    if (options_.fps > 0) capture.Set(cv::CAP_PROP_FPS, options_.fps);
  }
  nominal_fps_ = std::max(0.0, capture.Get(cv::CAP_PROP_FPS));

  devices::CameraFrame first;
  for (int attempt = 0; attempt < options_.max_consecutive_failures; ++attempt) {
    if (ReadFrame(&first)) break;
    if (!live_) break;
  }
  if (state_->bgr.empty()) {
    throw UserError("the " + what + " opened but delivered no frame");
  }
  width_ = state_->bgr.cols;
  height_ = state_->bgr.rows;
  if (options_.undistort) {
    if (options_.undistort->image_width != width_ || options_.undistort->image_height != height_) {
      throw UserError("the calibration is for " + std::to_string(options_.undistort->image_width) +
                      "x" + std::to_string(options_.undistort->image_height) + " frames but the " +
                      what + " delivers " + std::to_string(width_) + "x" + std::to_string(height_));
    }
    state_->undistorter.emplace(*options_.undistort);
    first.image = state_->undistorter->Apply(first.image);
  }
  state_->pending = std::move(first);
}

OpenCvCamera::~OpenCvCamera() = default;

bool OpenCvCamera::ReadFrame(devices::CameraFrame* frame) {
  VideoCaptureIo& capture = *state_->capture;
  bool ok = false;
  try {
    ok = capture.Read(state_->bgr) && !state_->bgr.empty();
  } catch (const cv::Exception&) {
    ok = false;  // a backend that throws mid-stream is treated like one that returns nothing
  }
  if (!ok) {
    ++failed_reads_;
    return false;
  }
  double timestamp_s = 0.0;
  if (live_) {
    timestamp_s = SteadySeconds();
    if (nominal_fps_ > 0.0 && last_timestamp_s_ >= 0.0) {
      const double periods = (timestamp_s - last_timestamp_s_) * nominal_fps_;
      if (periods > 1.5) {
        const int64_t lost = std::llround(periods) - 1;
        dropped_frames_ += lost;
        next_sequence_ += lost;
      }
    }
  } else {
    timestamp_s = loop_offset_s_ + capture.Get(cv::CAP_PROP_POS_MSEC) / 1000.0;
  }
  last_timestamp_s_ = timestamp_s;
  frame->image = RgbFromMat(state_->bgr, device_);
  frame->timestamp_s = timestamp_s;
  frame->sequence = next_sequence_++;
  return true;
}

devices::CameraFrame OpenCvCamera::Capture() {
  if (state_->pending) {
    devices::CameraFrame frame = std::move(*state_->pending);
    state_->pending.reset();
    ++frames_;
    return frame;
  }
  devices::CameraFrame frame;
  bool ok = false;
  if (live_) {
    for (int failures = 0; !ok && failures < options_.max_consecutive_failures; ++failures) {
      ok = ReadFrame(&frame);
    }
    if (!ok) {
      throw UserError("the camera " + device_ + " stopped delivering frames (" +
                      std::to_string(options_.max_consecutive_failures) +
                      " failed reads in a row; unplugged?) after " + std::to_string(frames_) +
                      " frames");
    }
  } else {
    ok = ReadFrame(&frame);
    if (!ok && options_.loop && frames_ > 0) {
      // The next loop starts one period after the last frame, so timestamps keep increasing.
      const double period_s = nominal_fps_ > 0.0 ? 1.0 / nominal_fps_ : 0.0;
      loop_offset_s_ = last_timestamp_s_ + period_s;
      state_->capture->Set(cv::CAP_PROP_POS_FRAMES, 0);
      ok = ReadFrame(&frame);
    }
    if (!ok) {
      throw UserError("the video file " + device_ + " ended after " + std::to_string(frames_) +
                      " frames");
    }
  }
  if (state_->undistorter) frame.image = state_->undistorter->Apply(frame.image);
  ++frames_;
  return frame;
}

std::string OpenCvCamera::Describe() const {
  std::string text = "OpenCV " + backend_ + (live_ ? " camera " : " video file ") + device_ + ", " +
                     std::to_string(width_) + "x" + std::to_string(height_);
  if (nominal_fps_ > 0.0) text += " at " + FormatFps(nominal_fps_) + " fps";
  if (state_->undistorter) text += ", undistorted";
  return text;
}

}  // namespace recon::camera
