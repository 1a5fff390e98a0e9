// The OpenCV I/O module (opencv_io.h): cv::VideoCapture, cv::imread and cv::imwrite behind the
// table the camera library loads on first use.

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "devices/camera/opencv_io.h"

namespace recon::camera {
namespace {

class Capture final : public VideoCaptureIo {
 public:
  bool OpenIndex(int index, int api) override { return capture_.open(index, api); }
  bool Open(const std::string& device, int api) override { return capture_.open(device, api); }
  bool IsOpened() const override { return capture_.isOpened(); }
  std::string BackendName() const override { return capture_.getBackendName(); }
  bool Set(int property, double value) override { return capture_.set(property, value); }
  double Get(int property) const override { return capture_.get(property); }
  bool Read(cv::Mat& bgr) override { return capture_.read(bgr); }

 private:
  cv::VideoCapture capture_;
};

std::unique_ptr<VideoCaptureIo> NewCapture() { return std::make_unique<Capture>(); }

void ReadImageFile(const std::string& path, cv::Mat& bgr) {
  bgr = cv::imread(path, cv::IMREAD_COLOR);
}

bool WriteImageFile(const std::string& path, const cv::Mat& bgr) { return cv::imwrite(path, bgr); }

const OpenCvIo kModule = {kOpenCvIoInterface, &NewCapture, &ReadImageFile, &WriteImageFile};

}  // namespace
}  // namespace recon::camera

extern "C" __attribute__((visibility("default"))) const recon::camera::OpenCvIo* ReconOpenCvIo() {
  return &recon::camera::kModule;
}
