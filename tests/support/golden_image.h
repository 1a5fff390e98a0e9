#pragma once

// Golden-image comparison for headless screenshot tests: a rendered screen is compared with a
// PNG under assets/goldens/ with a per-channel tolerance (antialiasing and llvmpipe rounding
// differ slightly between machines); on failure the actual image and a diff image are written
// next to each other so the change can be looked at, and `--update-goldens` refreshes them.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "engine/core/image.h"

namespace recon::testing {

/// Reads a PNG into an RgbImage, dropping alpha (colours are un-premultiplied, so a
/// half-transparent pixel reads back as the colour that was stored). Throws UserError naming the
/// path if the file is missing or is not a PNG.
RgbImage ReadPng(const std::string& path);

/// How two images differ. When the sizes differ nothing can be compared pixel by pixel: the
/// images count as entirely different (every pixel of the larger over tolerance, fraction 1,
/// max and mean difference 255), so a check on the numbers alone still fails.
struct ImageDifference {
  int width_a = 0;
  int height_a = 0;
  int width_b = 0;
  int height_b = 0;
  bool same_size = false;
  /// Pixels whose largest channel difference exceeds the per-channel tolerance.
  int64_t pixels_over_tolerance = 0;
  /// pixels_over_tolerance as a fraction of all pixels (0 for empty images).
  double fraction_over_tolerance = 0;
  /// The largest difference of any channel of any pixel, 0..255.
  int max_channel_difference = 0;
  /// The mean absolute difference over all channels of all pixels, 0..255.
  double mean_abs_difference = 0;
};

/// Compares `a` and `b` pixel by pixel. A pixel is over tolerance when any of its channels
/// differs by more than `per_channel_tolerance` (0..255). Throws std::invalid_argument if the
/// tolerance is out of range or an image's pixel buffer does not match its size.
ImageDifference CompareImages(const RgbImage& a, const RgbImage& b, int per_channel_tolerance);

/// A visualisation of where `golden` and `actual` differ: the golden faded to a light grey, and
/// each pixel over tolerance in pure red whose brightness grows with the difference (128 for
/// the smallest, 255 for the largest). If the sizes differ the result covers both, and the
/// pixels only one image has are full red. Same argument checks as CompareImages.
RgbImage DiffImage(const RgbImage& golden, const RgbImage& actual, int per_channel_tolerance);

/// How closely an image must match its golden, and where failures are written.
struct GoldenOptions {
  /// Channel differences up to this much are noise: antialiasing and llvmpipe rounding.
  int per_channel_tolerance = 8;
  /// 0.2 % of the pixels may differ by more (a moved glyph edge), not a changed widget.
  double max_fraction_over_tolerance = 0.002;
  /// Where `<name>.actual.png` and `<name>.diff.png` go on failure. Empty: $RECON_GOLDEN_FAILURES
  /// if set, else `<build>/golden-failures`.
  std::string failure_dir;
};

/// Compares `actual` with the golden PNG at `golden_path` (e.g. assets/goldens/main_window.png,
/// `<name>` being its file name without .png). Use as EXPECT_TRUE(MatchesGolden(...)).
///
/// - Within tolerance: success; stale `<name>.actual.png`/`<name>.diff.png` from an earlier
///   failed run are removed, so the failure folder only shows what fails now.
/// - Over tolerance or a different size: failure giving the numbers and the paths of the
///   written `<name>.actual.png` and `<name>.diff.png`.
/// - RECON_UPDATE_GOLDENS=1 in the environment (what `--update-goldens` sets, see
///   ParseGoldenFlags): the golden is created or rewritten from `actual` and the result is
///   success, with a message (also printed to stderr) saying which golden was written.
/// - A missing golden otherwise: failure saying how to create it; `actual` is written to the
///   failure folder so it can be looked at first.
///
/// Throws std::invalid_argument if the options are out of range.
::testing::AssertionResult MatchesGolden(const RgbImage& actual, const std::string& golden_path,
                                         const GoldenOptions& options = {});

/// Turns a `--update-goldens` command-line flag into RECON_UPDATE_GOLDENS=1 and removes it from
/// argv, so neither gtest nor the test's own argument handling sees a flag it does not know.
/// Call at the start of a test main, before ::testing::InitGoogleTest; recon_golden_main does.
void ParseGoldenFlags(int* argc, char** argv);

}  // namespace recon::testing
