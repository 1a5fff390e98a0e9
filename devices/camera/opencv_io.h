#pragma once

// OpenCV's video capture and image files (its videoio and imgcodecs libraries) are loaded when
// first needed. Together they pull in about 220 shared libraries (FFmpeg, GStreamer, GDAL, ...)
// that cost every process 0.2 s to map, though only a camera or an image file needs them: they
// live in one module, librecon_opencv_io.so (io/), that this opens with dlopen on first use.
// OpenCV's core (cv::Mat, cv::Exception) stays linked, so both sides share it. Internal to the
// camera library; the interface is C++, built by the same build.

#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace recon::camera {

/// The calls of cv::VideoCapture that OpenCvCamera makes; cv::Exception passes through.
class VideoCaptureIo {
 public:
  virtual ~VideoCaptureIo() = default;
  virtual bool OpenIndex(int index, int api) = 0;
  virtual bool Open(const std::string& device, int api) = 0;
  virtual bool IsOpened() const = 0;
  virtual std::string BackendName() const = 0;
  virtual bool Set(int property, double value) = 0;
  virtual double Get(int property) const = 0;
  virtual bool Read(cv::Mat& bgr) = 0;
};

/// What the module offers.
struct OpenCvIo {
  int interface_version = 0;
  std::unique_ptr<VideoCaptureIo> (*new_capture)() = nullptr;
  /// cv::imread(path, IMREAD_COLOR) into `bgr` (empty when unreadable).
  void (*read_image)(const std::string& path, cv::Mat& bgr) = nullptr;
  /// cv::imwrite(path, bgr).
  bool (*write_image)(const std::string& path, const cv::Mat& bgr) = nullptr;
};

/// Bumped with every change of the above.
constexpr int kOpenCvIoInterface = 1;
/// The module's one exported symbol: extern "C" const OpenCvIo* ReconOpenCvIo().
constexpr char kOpenCvIoEntry[] = "ReconOpenCvIo";

/// The module, loaded on first call (thread-safe). Its path is the one the build wrote it to, or
/// $RECON_OPENCV_IO_MODULE when set. UserError naming the path when it cannot be loaded.
const OpenCvIo& LoadOpenCvIo();

}  // namespace recon::camera
