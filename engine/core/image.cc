#include "engine/core/image.h"

#include <algorithm>

namespace recon {

RgbImage ImageFromObservation(const std::vector<float>& y, int size) {
  RgbImage image;
  const size_t plane = static_cast<size_t>(size) * size;
  if (size <= 0 || y.size() != 3 * plane) return image;
  image.width = image.height = size;
  image.rgb.resize(3 * plane);
  for (size_t p = 0; p < plane; ++p) {
    for (size_t c = 0; c < 3; ++c) {
      image.rgb[3 * p + c] = static_cast<uint8_t>(std::clamp(y[c * plane + p], 0.0f, 255.0f));
    }
  }
  return image;
}

}  // namespace recon
