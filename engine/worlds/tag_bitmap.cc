#include "engine/worlds/tag_bitmap.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <memory>
#include <string>

#include "engine/core/error.h"

namespace recon::worlds {
namespace {

struct FamilyDeleter {
  void operator()(apriltag_family_t* family) const { tag36h11_destroy(family); }
};
struct ImageDeleter {
  void operator()(image_u8_t* image) const { image_u8_destroy(image); }
};

// The 10 x 10 libapriltag bitmap, copied out of its padded (stride > width) buffer. A family is
// made per call: it is cheap, and sharing one would need a lock or a static initialiser that
// never frees it.
TagImage LibraryBitmap(int id) {
  if (id < 0 || id >= kTag36h11Count) {
    throw UserError("tag36h11 id " + std::to_string(id) + " is out of range 0.." +
                    std::to_string(kTag36h11Count - 1));
  }
  std::unique_ptr<apriltag_family_t, FamilyDeleter> family(tag36h11_create());
  std::unique_ptr<image_u8_t, ImageDeleter> image(apriltag_to_image(family.get(), id));
  TagImage bitmap;
  bitmap.size = image->width;
  bitmap.gray.resize(static_cast<size_t>(bitmap.size) * bitmap.size);
  for (int row = 0; row < bitmap.size; ++row) {
    for (int col = 0; col < bitmap.size; ++col) {
      bitmap.gray[static_cast<size_t>(row) * bitmap.size + col] =
          image->buf[static_cast<size_t>(row) * image->stride + col];
    }
  }
  return bitmap;
}

}  // namespace

TagImage TagBitmap(int id, int pixels_per_cell) {
  if (pixels_per_cell < 1) {
    throw UserError("TagBitmap: pixels_per_cell must be at least 1, got " +
                    std::to_string(pixels_per_cell));
  }
  const TagImage cells = LibraryBitmap(id);
  TagImage scaled;
  scaled.size = cells.size * pixels_per_cell;
  scaled.gray.resize(static_cast<size_t>(scaled.size) * scaled.size);
  for (int row = 0; row < scaled.size; ++row) {
    for (int col = 0; col < scaled.size; ++col) {
      scaled.gray[static_cast<size_t>(row) * scaled.size + col] =
          cells.At(row / pixels_per_cell, col / pixels_per_cell);
    }
  }
  return scaled;
}

std::vector<uint8_t> TagTextureRgb(int id, int size_px) {
  if (size_px < kTagGridCells) {
    throw UserError("TagTextureRgb: size_px must be at least " + std::to_string(kTagGridCells) +
                    " (one texel per cell), got " + std::to_string(size_px));
  }
  const int cell_px = size_px / kTagGridCells;
  const TagImage tag = TagBitmap(id, cell_px);
  const int offset = (size_px - tag.size) / 2;
  // White everywhere, then the tag (with its own one-cell quiet zone) pasted at `offset`.
  std::vector<uint8_t> rgb(static_cast<size_t>(size_px) * size_px * 3, 255);
  for (int row = 0; row < tag.size; ++row) {
    for (int col = 0; col < tag.size; ++col) {
      const size_t texel = (static_cast<size_t>(row + offset) * size_px + (col + offset)) * 3;
      const uint8_t value = tag.At(row, col);
      rgb[texel] = value;
      rgb[texel + 1] = value;
      rgb[texel + 2] = value;
    }
  }
  return rgb;
}

double TagBlackSideFraction(int size_px) {
  if (size_px < kTagGridCells) {
    throw UserError("TagBlackSideFraction: size_px must be at least " +
                    std::to_string(kTagGridCells) + ", got " + std::to_string(size_px));
  }
  return static_cast<double>(kTagBlackCells * (size_px / kTagGridCells)) / size_px;
}

}  // namespace recon::worlds
