#include "devices/camera/open_camera.h"

#include <filesystem>
#include <opencv2/core/utils/logger.hpp>

#include "devices/camera/image_sequence_camera.h"
#include "devices/camera/opencv_camera.h"

namespace recon::camera {

CameraSourceKind ClassifyCameraSource(const std::string& device) {
  std::error_code error;
  if (!device.empty() && std::filesystem::is_directory(device, error)) {
    return CameraSourceKind::kImageSequence;
  }
  bool digits = !device.empty() && device.size() <= 4;
  for (char c : device) digits = digits && c >= '0' && c <= '9';
  if (digits || device.rfind("/dev/", 0) == 0) return CameraSourceKind::kV4l2Device;
  return CameraSourceKind::kVideoFile;
}

std::unique_ptr<devices::Camera> OpenCamera(const std::string& device,
                                            const OpenCameraOptions& options) {
  if (ClassifyCameraSource(device) == CameraSourceKind::kImageSequence) {
    ImageSequenceOptions sequence;
    if (options.fps > 0.0) sequence.fps = options.fps;
    sequence.loop = options.loop;
    sequence.undistort = options.undistort;
    return std::make_unique<ImageSequenceCamera>(device, sequence);
  }
  OpenCvCameraOptions capture;
  capture.width = options.width;
  capture.height = options.height;
  capture.fps = options.fps;
  capture.loop = options.loop;
  capture.undistort = options.undistort;
  return std::make_unique<OpenCvCamera>(device, capture);
}

void SilenceOpenCvLogging() {
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
}

}  // namespace recon::camera
