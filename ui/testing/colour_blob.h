#pragma once

#include <functional>
#include <optional>

#include "engine/core/image.h"

namespace recon::ui {

/// A patch of one colour in an image, as a person picks an object out by its colour.
struct ColourBlob {
  float centre_x = 0, centre_y = 0;  ///< the centroid, in pixels
  int left = 0, top = 0, right = 0, bottom = 0;
  int pixels = 0;
};

/// Whether a pixel (red, green, blue) has the colour looked for.
using ColourTest = std::function<bool(int red, int green, int blue)>;

/// The largest 4-connected patch of pixels that pass `test`, or nothing when there is none of
/// at least `min_pixels`. Largest, so stray pixels of a similar colour elsewhere (a highlight, a
/// part of the robot) do not pull the centroid away.
std::optional<ColourBlob> LargestBlob(const RgbImage& image, const ColourTest& test,
                                      int min_pixels = 20);

}  // namespace recon::ui
