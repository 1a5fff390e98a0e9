#include "ui/testing/colour_blob.h"

#include <algorithm>
#include <vector>

namespace recon::ui {

std::optional<ColourBlob> LargestBlob(const RgbImage& image, const ColourTest& test,
                                      int min_pixels) {
  const int w = image.width, h = image.height;
  if (w <= 0 || h <= 0 || image.rgb.size() != static_cast<size_t>(w) * h * 3) return std::nullopt;
  std::vector<uint8_t> mask(static_cast<size_t>(w) * h);
  for (int i = 0; i < w * h; ++i) {
    const uint8_t* p = image.rgb.data() + 3 * static_cast<size_t>(i);
    mask[i] = test(p[0], p[1], p[2]) ? 1 : 0;
  }
  std::optional<ColourBlob> best;
  std::vector<int> stack;
  for (int start = 0; start < w * h; ++start) {
    if (mask[start] != 1) continue;
    ColourBlob blob{0, 0, w, h, -1, -1, 0};
    double sum_x = 0, sum_y = 0;
    mask[start] = 2;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int x = i % w, y = i / w;
      sum_x += x;
      sum_y += y;
      ++blob.pixels;
      blob.left = std::min(blob.left, x);
      blob.right = std::max(blob.right, x);
      blob.top = std::min(blob.top, y);
      blob.bottom = std::max(blob.bottom, y);
      const int neighbours[4] = {x > 0 ? i - 1 : -1, x + 1 < w ? i + 1 : -1, y > 0 ? i - w : -1,
                                 y + 1 < h ? i + w : -1};
      for (int n : neighbours) {
        if (n >= 0 && mask[n] == 1) {
          mask[n] = 2;
          stack.push_back(n);
        }
      }
    }
    if (blob.pixels >= min_pixels && (!best || blob.pixels > best->pixels)) {
      blob.centre_x = static_cast<float>(sum_x / blob.pixels);
      blob.centre_y = static_cast<float>(sum_y / blob.pixels);
      best = blob;
    }
  }
  return best;
}

}  // namespace recon::ui
