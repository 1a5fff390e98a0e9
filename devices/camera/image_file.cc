#include "devices/camera/image_file.h"

#include "devices/camera/opencv_image.h"
#include "devices/camera/opencv_io.h"
#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::camera {

RgbImage ReadImage(const std::string& path) {
  RefuseNonRegularFile(path);
  const OpenCvIo& io = LoadOpenCvIo();
  cv::Mat bgr;
  try {
    io.read_image(path, bgr);
  } catch (const cv::Exception& e) {
    throw UserError("cannot read the image " + path + ": " + e.err);
  }
  if (bgr.empty()) throw UserError("cannot read the image " + path + ": not a readable image");
  return RgbFromMat(bgr, path);
}

void WriteImage(const std::string& path, const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    throw UserError("cannot write " + path + ": the image is empty or malformed");
  }
  const OpenCvIo& io = LoadOpenCvIo();
  bool ok = false;
  try {
    ok = io.write_image(path, BgrFromRgb(image));
  } catch (const cv::Exception& e) {
    throw UserError("cannot write the image " + path + ": " + e.err);
  }
  if (!ok) throw UserError("cannot write the image " + path);
}

}  // namespace recon::camera
