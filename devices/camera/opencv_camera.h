#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "devices/camera/camera_calibration_file.h"
#include "engine/devices/camera.h"

namespace recon::camera {

/// How to open an OpenCvCamera.
struct OpenCvCameraOptions {
  /// Requested frame size and rate for a live device (0 = the driver's default). The driver may
  /// pick the nearest mode it has; width(), height() and nominal_fps() report what it chose.
  /// Ignored for video files.
  int width = 0;
  int height = 0;
  double fps = 0.0;
  /// Requested pixel format of a live device, e.g. "MJPG" (USB webcams reach their full frame
  /// rate at high resolutions only with it). Empty: the driver's default.
  std::string fourcc;
  /// Video files: start again at the first frame at the end instead of failing.
  bool loop = false;
  /// Live devices: this many failed reads in a row mean the camera is gone (unplugged).
  int max_consecutive_failures = 30;
  /// When set, every frame is undistorted with it (see Undistorter).
  std::optional<CameraCalibration> undistort;
};

/// A devices::Camera over cv::VideoCapture: a V4L2 device ("/dev/video0" or an index "0") or a
/// video file. Frames come back as RGB. Timestamps are the host's steady clock (seconds since its
/// epoch) at the end of the read for live devices, and the file's own presentation time
/// (CAP_PROP_POS_MSEC, continued across loops) for files. Not thread-safe.
class OpenCvCamera : public devices::Camera {
 public:
  /// Opens `device`: a string of digits is a V4L2 index, a path under /dev/ a V4L2 device, and
  /// anything else a video file. Throws UserError naming the device when it cannot be opened or
  /// delivers no first frame, and when `options.undistort` was made for another frame size.
  explicit OpenCvCamera(const std::string& device, OpenCvCameraOptions options = {});
  ~OpenCvCamera() override;

  /// The next frame. Throws UserError naming the device when a live device stops delivering
  /// (max_consecutive_failures failed reads in a row) or a file ends without `loop`.
  devices::CameraFrame Capture() override;
  /// E.g. "OpenCV V4L2 camera /dev/video0, 640x480 at 30 fps".
  std::string Describe() const override;

  const std::string& device() const { return device_; }
  bool is_live() const { return live_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// The rate the driver or the file claims (0 when it does not say).
  double nominal_fps() const { return nominal_fps_; }
  /// OpenCV's name for the backend in use: "V4L2", "FFMPEG", "CV_MJPEG", ...
  const std::string& backend() const { return backend_; }

  /// Frames delivered so far.
  int64_t frames() const { return frames_; }
  /// Reads that returned no frame (each retried), over the whole run.
  int64_t failed_reads() const { return failed_reads_; }
  /// Frames estimated lost on a live device: a gap between timestamps of more than 1.5 nominal
  /// periods counts its missing periods. Sequence numbers skip by the same amount.
  int64_t dropped_frames() const { return dropped_frames_; }

 private:
  struct State;
  bool ReadFrame(devices::CameraFrame* frame);

  std::string device_;
  OpenCvCameraOptions options_;
  std::unique_ptr<State> state_;
  bool live_ = false;
  int width_ = 0;
  int height_ = 0;
  double nominal_fps_ = 0.0;
  std::string backend_;
  int64_t frames_ = 0;
  int64_t failed_reads_ = 0;
  int64_t dropped_frames_ = 0;
  int64_t next_sequence_ = 0;
  double last_timestamp_s_ = -1.0;
  double loop_offset_s_ = 0.0;  // files: presentation time added for each completed loop
};

}  // namespace recon::camera
