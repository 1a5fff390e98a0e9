#pragma once

// An independent implementation of the Dynamic 2D image rules of REFERENCE.md section 2, written
// pixel-first (which item covers this pixel?) instead of item-first like the world, so the two
// can only agree if both follow the rules.

#include <array>
#include <cmath>
#include <vector>

#include "engine/worlds/dynamic2d.h"

namespace recon::worlds::testing {

// round(32 (s + 12) / 24) with ties to even, spelled out by hand.
inline long RoundHalfEvenIndex(double s) {
  const double v = 32.0 * (s + 12.0) / 24.0;
  const double f = std::floor(v);
  const double frac = v - f;
  long i = static_cast<long>(f);
  if (frac > 0.5 || (frac == 0.5 && i % 2 != 0)) ++i;
  return i;
}

// True when pixel index p lies in the item's block {i-1, i} once the indices are clipped to
// [0, 31].
inline bool Covers(double s, int p) {
  const long i = RoundHalfEvenIndex(s);
  for (long k : {i - 1, i}) {
    const long clipped = k < 0 ? 0 : (k > 31 ? 31 : k);
    if (clipped == p) return true;
  }
  return false;
}

// Items at a non-finite position (a diverged rollout) are not drawn.
inline bool CoversPixel(const Vec2& item, int a, int b) {
  if (!std::isfinite(item[0]) || !std::isfinite(item[1])) return false;
  return Covers(item[0], a) && Covers(item[1], b);
}

// The expected 3x32x32 image of `state` over `background`.
inline std::vector<float> ExpectedImage(const Dynamic2DState& state,
                                        const std::vector<float>& background) {
  std::vector<float> image(3 * 32 * 32);
  for (int a = 0; a < 32; ++a) {
    for (int b = 0; b < 32; ++b) {
      std::array<float, 3> rgb;
      for (int c = 0; c < 3; ++c) rgb[c] = background[c * 1024 + a * 32 + b];
      if (CoversPixel(state.robot, a, b)) rgb[0] = rgb[1] = 0.0f;
      for (int o = 0; o < 4; ++o) {  // later objects overwrite earlier ones
        if (!CoversPixel(state.objects[o], a, b)) continue;
        const double c = state.colours[o];
        rgb = {static_cast<float>(c / 10 * 255), static_cast<float>((1 - c / 10) * 255), 0.0f};
      }
      for (int c = 0; c < 3; ++c) image[c * 1024 + a * 32 + b] = rgb[c];
    }
  }
  return image;
}

}  // namespace recon::worlds::testing
