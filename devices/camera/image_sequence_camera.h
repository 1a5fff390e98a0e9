#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/undistorter.h"
#include "engine/devices/camera.h"

namespace recon::camera {

/// How an ImageSequenceCamera serves its frames.
struct ImageSequenceOptions {
  /// Frame k is stamped k / fps seconds (k counts on across loops).
  double fps = 30.0;
  /// At the last frame, start again at the first instead of failing.
  bool loop = false;
  /// Make Capture wait until frame k's time (k / fps after the first Capture) has come, as a
  /// real camera would; timestamps stay k / fps. Off: frames come as fast as they are asked for.
  bool real_time = false;
  /// When set, every frame is undistorted with it (see Undistorter).
  std::optional<CameraCalibration> undistort;
};

/// The fake camera: a folder of PNG/JPG frames (extensions .png, .jpg, .jpeg in any case),
/// served in file-name order (plain byte order, as `ls` sorts in the C locale: number the files
/// with leading zeros). For tests, demos and replaying a recorded lab scene without the lab.
/// All frames must have the first one's size. Files are read as they are served.
class ImageSequenceCamera : public devices::Camera {
 public:
  /// Lists the folder and reads the first frame. Throws UserError naming the folder when it does
  /// not exist or holds no image, naming the file when the first frame is unreadable, and for a
  /// non-positive fps or a calibration made for another frame size.
  explicit ImageSequenceCamera(const std::string& folder, ImageSequenceOptions options = {});

  /// The next frame. Throws UserError naming the file when it cannot be read or has another size
  /// than the first, and naming the folder at the end of the sequence without `loop`.
  devices::CameraFrame Capture() override;
  /// E.g. "image sequence /data/scene (120 frames), 640x480 at 30 fps".
  std::string Describe() const override;

  const std::vector<std::string>& files() const { return files_; }
  int width() const { return width_; }
  int height() const { return height_; }
  double fps() const { return options_.fps; }

 private:
  RgbImage Load(const std::string& file) const;

  std::string folder_;
  ImageSequenceOptions options_;
  std::vector<std::string> files_;
  int width_ = 0;
  int height_ = 0;
  int64_t next_ = 0;      // frames served so far, across loops
  double start_s_ = 0.0;  // steady clock at the first Capture, for real_time pacing
  std::optional<Undistorter> undistorter_;
};

}  // namespace recon::camera
