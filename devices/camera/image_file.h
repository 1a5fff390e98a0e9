#pragma once

#include <string>

#include "engine/core/image.h"

namespace recon::camera {

/// Reads a PNG/JPG/... image file as RGB (cv::imread). Throws UserError naming `path` when it is
/// missing or not a readable image.
RgbImage ReadImage(const std::string& path);

/// Writes `image` in the format its extension names (.png, .jpg, ...) with cv::imwrite. Throws
/// UserError naming `path` when it cannot be written or the image is malformed.
void WriteImage(const std::string& path, const RgbImage& image);

}  // namespace recon::camera
