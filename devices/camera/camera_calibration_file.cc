#include "devices/camera/camera_calibration_file.h"

#include <filesystem>
#include <opencv2/core.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::camera {

namespace {

bool ValidDistortionCount(size_t n) {
  return n == 0 || n == 4 || n == 5 || n == 8 || n == 12 || n == 14;
}

// A matrix node: cv::FileStorage's !!opencv-matrix is a map {rows, cols, dt, data}, and so is a
// ROS camera_info matrix without the tag, so reading the map by hand accepts both.
std::vector<double> ReadMatrix(const cv::FileNode& node, const std::string& path,
                               const std::string& key, int* rows, int* cols) {
  auto bad = [&](const std::string& why) { return UserError(path + ": key '" + key + "' " + why); };
  if (node.empty() || node.isNone()) throw bad("is missing");
  if (!node.isMap()) throw bad("is not a matrix (expected rows, cols and data)");
  const cv::FileNode r = node["rows"], c = node["cols"], data = node["data"];
  if (!r.isInt() || !c.isInt()) throw bad("has no integer rows/cols");
  if (!data.isSeq()) throw bad("has no data list");
  *rows = static_cast<int>(r);
  *cols = static_cast<int>(c);
  if (*rows < 0 || *cols < 0 || static_cast<size_t>(*rows) * *cols != data.size()) {
    throw bad("holds " + std::to_string(data.size()) + " values for a " + std::to_string(*rows) +
              "x" + std::to_string(*cols) + " matrix");
  }
  std::vector<double> values;
  for (const cv::FileNode& v : data) {
    if (!v.isReal() && !v.isInt()) throw bad("has a value that is not a number");
    values.push_back(static_cast<double>(v));
  }
  return values;
}

int ReadPositiveInt(const cv::FileStorage& fs, const std::string& path, const std::string& key) {
  const cv::FileNode node = fs[key];
  if (node.empty() || node.isNone()) throw UserError(path + ": key '" + key + "' is missing");
  if (!node.isInt() || static_cast<int>(node) <= 0) {
    throw UserError(path + ": key '" + key + "' must be a positive integer");
  }
  return static_cast<int>(node);
}

void Validate(const CameraCalibration& c, const std::string& path) {
  if (c.image_width <= 0 || c.image_height <= 0) {
    throw UserError(path + ": image_width and image_height must be positive");
  }
  const Eigen::Matrix3d& k = c.camera_matrix;
  if (!(k(0, 0) > 0.0) || !(k(1, 1) > 0.0)) {
    throw UserError(path + ": key 'camera_matrix' must have positive focal lengths fx, fy");
  }
  if (k(2, 0) != 0.0 || k(2, 1) != 0.0 || k(2, 2) != 1.0) {
    throw UserError(path + ": key 'camera_matrix' must have the last row 0 0 1");
  }
  if (!ValidDistortionCount(c.distortion.size())) {
    throw UserError(path + ": key 'distortion_coefficients' has " +
                    std::to_string(c.distortion.size()) +
                    " values; OpenCV knows 4, 5, 8, 12 or 14");
  }
}

}  // namespace

tags::CameraIntrinsics CameraCalibration::ToIntrinsics() const {
  tags::CameraIntrinsics out;
  out.fx = camera_matrix(0, 0);
  out.fy = camera_matrix(1, 1);
  // OpenCV puts pixel (c, r)'s centre at (c, r); tags::CameraIntrinsics (like libapriltag's
  // detections) at (c + 0.5, r + 0.5). The same optical axis is therefore half a pixel further
  // right and down in our coordinates. Forgetting this biases every located tag by half a pixel.
  out.cx = camera_matrix(0, 2) + 0.5;
  out.cy = camera_matrix(1, 2) + 0.5;
  out.width = image_width;
  out.height = image_height;
  return out;
}

CameraCalibration CameraCalibration::FromIntrinsics(const tags::CameraIntrinsics& intrinsics) {
  CameraCalibration c;
  c.image_width = intrinsics.width;
  c.image_height = intrinsics.height;
  c.camera_matrix << intrinsics.fx, 0.0, intrinsics.cx - 0.5,  //
      0.0, intrinsics.fy, intrinsics.cy - 0.5,                 //
      0.0, 0.0, 1.0;
  return c;
}

bool CameraCalibration::HasNoDistortion() const {
  for (double d : distortion) {
    if (d != 0.0) return false;
  }
  return true;
}

CameraCalibration ReadCameraCalibration(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw UserError("cannot read the camera calibration " + path + ": no such file");
  }
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError("cannot read the camera calibration " + path);
  std::string content = *text;
  const size_t first = content.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) throw UserError(path + ": empty file, not a camera calibration");
  // OpenCV's YAML parser insists on the "%YAML" directive that cv::FileStorage writes; ROS and
  // hand-written files leave it out. XML and JSON start with '<' or '{'.
  if (content.compare(0, 5, "%YAML") != 0 && content[first] != '<' && content[first] != '{') {
    content = "%YAML:1.0\n---\n" + content;
  }
  cv::FileStorage fs;
  try {
    if (!fs.open(content, cv::FileStorage::READ | cv::FileStorage::MEMORY)) {
      throw UserError("cannot read the camera calibration " + path);
    }
  } catch (const cv::Exception& e) {
    // OpenCV's parser throws for anything that is not YAML/XML/JSON; its message names its own
    // source file, so only the gist is kept.
    throw UserError(path + ": not a camera calibration file (OpenCV could not parse it: " + e.err +
                    ")");
  }
  CameraCalibration c;
  c.image_width = ReadPositiveInt(fs, path, "image_width");
  c.image_height = ReadPositiveInt(fs, path, "image_height");
  int rows = 0, cols = 0;
  const std::vector<double> k =
      ReadMatrix(fs["camera_matrix"], path, "camera_matrix", &rows, &cols);
  if (rows != 3 || cols != 3) {
    throw UserError(path + ": key 'camera_matrix' is " + std::to_string(rows) + "x" +
                    std::to_string(cols) + ", expected 3x3");
  }
  for (int i = 0; i < 9; ++i) c.camera_matrix(i / 3, i % 3) = k[i];
  c.distortion =
      ReadMatrix(fs["distortion_coefficients"], path, "distortion_coefficients", &rows, &cols);
  if (rows != 1 && cols != 1) {
    throw UserError(path + ": key 'distortion_coefficients' is " + std::to_string(rows) + "x" +
                    std::to_string(cols) + ", expected one row or one column");
  }
  Validate(c, path);
  return c;
}

void WriteCameraCalibration(const std::string& path, const CameraCalibration& calibration) {
  Validate(calibration, path);
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs << "image_width" << calibration.image_width;
  fs << "image_height" << calibration.image_height;
  cv::Mat k(3, 3, CV_64F);
  for (int i = 0; i < 9; ++i) k.at<double>(i / 3, i % 3) = calibration.camera_matrix(i / 3, i % 3);
  fs << "camera_matrix" << k;
  // No distortion is written as five zeros, the form OpenCV's own tools expect.
  std::vector<double> coefficients = calibration.distortion;
  if (coefficients.empty()) coefficients.assign(5, 0.0);
  cv::Mat d(1, static_cast<int>(coefficients.size()), CV_64F);
  for (size_t i = 0; i < coefficients.size(); ++i) {
    d.at<double>(0, static_cast<int>(i)) = coefficients[i];
  }
  fs << "distortion_coefficients" << d;
  WriteFileAtomically(path, fs.releaseAndGetString());
}

}  // namespace recon::camera
