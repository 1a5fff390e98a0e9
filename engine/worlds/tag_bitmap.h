#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace recon::worlds {

/// tag36h11 as libapriltag draws it (apriltag_to_image): a 10 x 10 grid of cells.
///   ring 0 (rows/cols 0 and 9): white quiet zone, one cell wide;
///   ring 1 (rows/cols 1 and 8): the black border, whose outer edge (8 cells) is the "tag size"
///                              that pose estimation expects;
///   cells 2..7:                 the 6 x 6 data bits (white = 1).
/// Row 0 is the top of the tag as printed: the orientation AprilTag's own PNGs and PDFs use.
inline constexpr int kTag36h11Count = 587;
inline constexpr int kTagGridCells = 10;
inline constexpr int kTagBlackCells = 8;

/// A square 8-bit grey image, row 0 at the top, `size * size` bytes, 0 black and 255 white.
/// Its own type rather than an RgbImage because the tag is two-valued and tests compare it cell by
/// cell; TagTextureRgb below gives the RGB form.
struct TagImage {
  int size = 0;
  std::vector<uint8_t> gray;

  uint8_t At(int row, int col) const { return gray[static_cast<size_t>(row) * size + col]; }
};

/// The tag36h11 bitmap of `id` (0..586), including its one-cell white quiet zone, scaled by
/// nearest neighbour to `pixels_per_cell` pixels per cell: size = 10 * pixels_per_cell.
/// Throws UserError for an id out of range or pixels_per_cell < 1.
TagImage TagBitmap(int id, int pixels_per_cell);

/// An RGB8 texture of tag36h11 `id`, exactly `size_px` x `size_px` (size_px >= 10), for MuJoCo's
/// tex_rgb (3 bytes per texel, rows consecutive, no padding).
///
/// Each cell is size_px / 10 texels (integer division); the r = size_px % 10 texels left over widen
/// the white quiet zone, floor(r / 2) on the top and left and the rest on the bottom and right.
/// So the quiet zone is always at least one cell, and when size_px is a multiple of 10 (the
/// recommended case) the tag is exactly centred; otherwise its centre sits half a texel
/// up-left of the texture centre when r is odd. Size the geom with TagBlackSideFraction.
///
/// Row 0 is the top of the tag as printed. MuJoCo uploads row 0 as texture coordinate v = 0.
/// Measured with MuJoCo 2.2.2 (offscreen EGL render; this texture written into tex_rgb of a
/// type="2d" texture whose material keeps the default texrepeat="1 1", texuniform="false"; on a
/// plane geom and on a box's +z face; camera looking down with image up = the geom's +y): row 0
/// lands on the geom's +y edge, so the tag appears upright, as printed, and is detected with its
/// id. The same texture with its rows reversed is a MIRROR image, which AprilTag does not decode
/// at all (a rotation would not matter): do not flip rows "to fix" MuJoCo's v axis, and if a
/// scene maps textures differently, check with one rendered frame that the tag is detected.
std::vector<uint8_t> TagTextureRgb(int id, int size_px);

/// The fraction of TagTextureRgb's side covered by the black border's outer edge, i.e.
/// 8 * (size_px / 10) / size_px: a texture mapped onto a square of side S metres shows a tag of
/// size S * TagBlackSideFraction(size_px) metres (0.8 when size_px is a multiple of 10).
double TagBlackSideFraction(int size_px);

}  // namespace recon::worlds
