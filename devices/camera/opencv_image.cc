#include "devices/camera/opencv_image.h"

#include <cstring>
#include <opencv2/imgproc.hpp>

#include "engine/core/error.h"

namespace recon::camera {

RgbImage RgbFromMat(const cv::Mat& image, const std::string& source) {
  if (image.empty()) throw UserError(source + ": empty image");
  if (image.depth() != CV_8U) throw UserError(source + ": not an 8-bit image");
  cv::Mat rgb;
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, rgb, cv::COLOR_GRAY2RGB);
      break;
    case 3:
      cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
      break;
    case 4:
      cv::cvtColor(image, rgb, cv::COLOR_BGRA2RGB);
      break;
    default:
      throw UserError(source + ": unsupported image with " + std::to_string(image.channels()) +
                      " channels");
  }
  RgbImage out;
  out.width = rgb.cols;
  out.height = rgb.rows;
  out.rgb.resize(static_cast<size_t>(rgb.cols) * rgb.rows * 3);
  const size_t row_bytes = static_cast<size_t>(rgb.cols) * 3;
  for (int r = 0; r < rgb.rows; ++r) {
    std::memcpy(out.rgb.data() + r * row_bytes, rgb.ptr<uint8_t>(r), row_bytes);
  }
  return out;
}

cv::Mat BgrFromRgb(const RgbImage& image) {
  // The wrapper only reads the buffer: cvtColor writes into a new Mat.
  const cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

}  // namespace recon::camera
