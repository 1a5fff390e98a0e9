#include "engine/report/chart.h"

#include <array>

namespace recon::report {

Color PaletteColor(int index) {
  // Okabe-Ito, reordered so that neighbours contrast most and the weak yellow comes late; black
  // is replaced by grey because whiskers and text are black.
  static constexpr std::array<Color, 8> kPalette = {{
      {0.000, 0.447, 0.698},  // blue
      {0.902, 0.624, 0.000},  // orange
      {0.000, 0.620, 0.451},  // bluish green
      {0.835, 0.369, 0.000},  // vermillion
      {0.337, 0.706, 0.914},  // sky blue
      {0.800, 0.475, 0.655},  // reddish purple
      {0.941, 0.894, 0.259},  // yellow
      {0.600, 0.600, 0.600},  // grey
  }};
  constexpr int kHues = static_cast<int>(kPalette.size());
  constexpr int kCycle = 3 * kHues;
  const int wrapped = ((index % kCycle) + kCycle) % kCycle;
  const Color base = kPalette[wrapped % kHues];
  // Past eight entries the hues repeat, darker then lighter, so the ninth bar is not mistaken
  // for the first; lightness differences survive every kind of colour blindness.
  switch (wrapped / kHues) {
    case 1:
      return {base.r * 0.6, base.g * 0.6, base.b * 0.6};
    case 2:
      return {0.55 * base.r + 0.45, 0.55 * base.g + 0.45, 0.55 * base.b + 0.45};
    default:
      return base;
  }
}

}  // namespace recon::report
