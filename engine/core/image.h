#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace recon {

/// An 8-bit RGB image, rows top to bottom, pixels interleaved (HWC), as cameras deliver them and
/// as robomimic stores them.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< width * height * 3 bytes

  const uint8_t* Pixel(int row, int col) const {
    return rgb.data() + (static_cast<size_t>(row) * width + col) * 3;
  }
};

/// A camera observation y (3 x size x size, channels first, 0-255, as the policies read it) as an
/// image to show; empty when y is not of that size.
RgbImage ImageFromObservation(const std::vector<float>& y, int size);

}  // namespace recon
