#include "engine/learn/augmentation.h"

#include <algorithm>
#include <cmath>

namespace recon::learn {

void ShiftImage(const float* image, int channels, int height, int width, int dy, int dx,
                float* out) {
  for (int c = 0; c < channels; ++c) {
    const float* plane = image + static_cast<int64_t>(c) * height * width;
    float* target = out + static_cast<int64_t>(c) * height * width;
    for (int r = 0; r < height; ++r) {
      const float* row = plane + static_cast<int64_t>(std::clamp(r + dy, 0, height - 1)) * width;
      float* dest = target + static_cast<int64_t>(r) * width;
      // Columns left of the image repeat its first pixel, those right of it its last.
      const int first = std::clamp(-dx, 0, width), last = std::clamp(width - dx, 0, width);
      std::fill(dest, dest + first, row[0]);
      std::copy(row + first + dx, row + last + dx, dest + first);
      std::fill(dest + last, dest + width, row[width - 1]);
    }
  }
}

Shift DrawShift(Rng& rng, int pad) {
  const uint64_t span = static_cast<uint64_t>(2 * pad + 1);
  Shift s;
  s.dy = static_cast<int>(rng.UniformInt(span)) - pad;
  s.dx = static_cast<int>(rng.UniformInt(span)) - pad;
  return s;
}

Erase DrawErase(Rng& rng, int height, int width, int side) {
  Erase e;
  e.side = std::clamp(side, 0, std::min(height, width));
  e.row = static_cast<int>(rng.UniformInt(static_cast<uint64_t>(height - e.side + 1)));
  e.col = static_cast<int>(rng.UniformInt(static_cast<uint64_t>(width - e.side + 1)));
  return e;
}

void EraseSquare(float* image, int channels, int height, int width, const Erase& erase) {
  const int64_t plane_size = static_cast<int64_t>(height) * width;
  for (int c = 0; c < channels; ++c) {
    float* plane = image + c * plane_size;
    double sum = 0;
    for (int64_t i = 0; i < plane_size; ++i) sum += plane[i];
    const auto mean = static_cast<float>(sum / static_cast<double>(plane_size));
    for (int r = erase.row; r < erase.row + erase.side; ++r) {
      std::fill(plane + static_cast<int64_t>(r) * width + erase.col,
                plane + static_cast<int64_t>(r) * width + erase.col + erase.side, mean);
    }
  }
}

void FeatureNoiseOffsets(const float* phi, int batch, int k, double sigma, const float* noise,
                         float* offsets) {
  for (int i = 0; i < k; ++i) {
    double sum = 0, sum_sq = 0;
    for (int b = 0; b < batch; ++b) {
      const double v = phi[static_cast<size_t>(b) * k + i];
      sum += v;
      sum_sq += v * v;
    }
    const double mean = sum / batch;
    const double sd = std::sqrt(std::max(0.0, sum_sq / batch - mean * mean));
    for (int b = 0; b < batch; ++b) {
      const size_t at = static_cast<size_t>(b) * k + i;
      offsets[at] = static_cast<float>(sigma * sd * noise[at]);
    }
  }
}

}  // namespace recon::learn
