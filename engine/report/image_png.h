#pragma once

#include <string>

#include "engine/core/image.h"

namespace recon::report {

/// Writes an RGB image as a PNG file, atomically (a half-written file never replaces a good
/// one). UserError naming the path if it cannot be written.
void WritePng(const RgbImage& image, const std::string& path);

}  // namespace recon::report
