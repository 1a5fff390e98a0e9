#pragma once

#include <memory>
#include <optional>
#include <string>

#include "devices/camera/camera_calibration_file.h"
#include "engine/devices/camera.h"

namespace recon::camera {

/// What a `--device` string asks for, as OpenCamera reads it.
enum class CameraSourceKind {
  kV4l2Device,     ///< "/dev/video0" or an index "0"
  kVideoFile,      ///< a file OpenCV's video backends read (.avi, .mp4, ...)
  kImageSequence,  ///< a folder of PNG/JPG frames (the fake camera)
};

/// Options shared by every kind of source; each kind uses the ones that apply to it.
struct OpenCameraOptions {
  int width = 0;  ///< live devices: requested size (0 = driver default)
  int height = 0;
  double fps = 0.0;   ///< live devices: requested rate; image sequences: serving rate (0 = 30)
  bool loop = false;  ///< files and image sequences: start again at the end
  std::optional<CameraCalibration> undistort;  ///< undistort every frame with this
};

/// Which kind `device` names: a folder is an image sequence, digits or a /dev/ path a V4L2
/// device, anything else a video file. Does not open it.
CameraSourceKind ClassifyCameraSource(const std::string& device);

/// Opens `device` as ClassifyCameraSource says (OpenCvCamera or ImageSequenceCamera). Throws
/// UserError naming the device when it cannot be opened.
std::unique_ptr<devices::Camera> OpenCamera(const std::string& device,
                                            const OpenCameraOptions& options = {});

/// Silences OpenCV's own log lines ("can't open camera by index", GStreamer warnings) for the
/// whole process. For command-line programs, whose UserErrors already say what went wrong.
void SilenceOpenCvLogging();

}  // namespace recon::camera
