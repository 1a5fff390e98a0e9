#pragma once

// Internal to devices/camera and its tests: conversions between OpenCV's images and RgbImage.
// The public headers of devices/camera do not include OpenCV; this one does.

#include <opencv2/core.hpp>
#include <string>

#include "engine/core/image.h"

namespace recon::camera {

/// A copy of an 8-bit OpenCV image (BGR, BGRA or grey, as capture and imread deliver) as RGB.
/// Throws UserError, naming `source`, for an empty image or another pixel type.
RgbImage RgbFromMat(const cv::Mat& image, const std::string& source);

/// A BGR cv::Mat copy of `image`, ready for imwrite or VideoWriter.
cv::Mat BgrFromRgb(const RgbImage& image);

}  // namespace recon::camera
