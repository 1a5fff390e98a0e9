#pragma once

// Random-shift image augmentation (Kostrikov et al., DrQ 2020): pad the image by `pad` pixels,
// replicating the border, and crop it back to its size at a random offset. A few demonstrations
// show the camera the same few scenes; shifting them by a few pixels teaches the feature network
// that a pixel's exact place carries less than what is there. Training only: a policy acting sees
// the image as it is.
//
// Random erasing (cutout; DeVries & Taylor 2017, RAD 2020): a square of the image is painted
// over with the image's own mean colour. A bowl that moves between scenes is a local change of
// the image; a few demonstrations never show the policy that such a change should not move it,
// and erasing a random patch of every training image does.
//
// Also feature noise (TrainConfig::feature_noise): the other augmentation, on the features the
// policy reads rather than on the image.

#include <cstdint>

#include "engine/core/rng.h"

namespace recon::learn {

/// The largest shift TrainConfig::random_shift_px accepts (in pixels).
constexpr int kMaxRandomShiftPx = 16;

/// Feature noise (TrainConfig::feature_noise) for the features `phi` of a batch ([batch][k],
/// row-major): offsets[b][i] = sigma * sd_i * noise[b][i], with sd_i feature i's standard
/// deviation over the batch (divided by the batch size, as PyTorch's std(unbiased=False)) and
/// `noise` standard normal draws.
void FeatureNoiseOffsets(const float* phi, int batch, int k, double sigma, const float* noise,
                         float* offsets);

/// Writes `image` (channels-first, channels x height x width) shifted by (dy, dx) pixels into
/// `out`: out(c, r, k) = image(c, clamp(r + dy), clamp(k + dx)), i.e. the border replicated.
void ShiftImage(const float* image, int channels, int height, int width, int dy, int dx,
                float* out);

/// One draw of a shift in [-pad, pad] per axis from `rng` (dy first, then dx).
struct Shift {
  int dy = 0, dx = 0;
};
Shift DrawShift(Rng& rng, int pad);

/// Where a square of `side` pixels is erased: its top-left corner, drawn uniformly so that the
/// square lies inside a height x width image (row first, then column). A side larger than the
/// image is clipped to it.
struct Erase {
  int row = 0, col = 0, side = 0;
};
Erase DrawErase(Rng& rng, int height, int width, int side);

/// Paints the square `erase` of `image` (channels-first, in place) with each channel's mean over
/// the whole image, taken before the square is painted.
void EraseSquare(float* image, int channels, int height, int width, const Erase& erase);

}  // namespace recon::learn
