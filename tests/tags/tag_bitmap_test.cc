#include "engine/worlds/tag_bitmap.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace recon::worlds {
namespace {

// Suite names spell "Apriltag" so that `ctest -R tag` selects them.
constexpr int kIds[] = {0, 1, 7, 42, 100, 311, 586};

TEST(ApriltagBitmapTest, MatchesLibapriltagCellForCellForSeveralIds) {
  apriltag_family_t* family = tag36h11_create();
  for (const int id : kIds) {
    image_u8_t* reference = apriltag_to_image(family, id);
    const TagImage bitmap = TagBitmap(id, 1);
    ASSERT_EQ(bitmap.size, kTagGridCells);
    ASSERT_EQ(reference->width, kTagGridCells);
    ASSERT_EQ(reference->height, kTagGridCells);
    ASSERT_EQ(bitmap.gray.size(), 100u);
    for (int row = 0; row < kTagGridCells; ++row) {
      for (int col = 0; col < kTagGridCells; ++col) {
        EXPECT_EQ(bitmap.At(row, col), reference->buf[row * reference->stride + col])
            << "id " << id << " cell (" << row << ", " << col << ")";
      }
    }
    image_u8_destroy(reference);
  }
  tag36h11_destroy(family);
}

TEST(ApriltagBitmapTest, QuietZoneIsWhiteBorderIsBlackAndDataDiffersBetweenIds) {
  std::vector<std::vector<uint8_t>> data_cells;
  for (const int id : kIds) {
    const TagImage bitmap = TagBitmap(id, 1);
    for (int i = 0; i < kTagGridCells; ++i) {
      // Ring 0: the one-cell white quiet zone.
      EXPECT_EQ(bitmap.At(0, i), 255) << "id " << id;
      EXPECT_EQ(bitmap.At(9, i), 255) << "id " << id;
      EXPECT_EQ(bitmap.At(i, 0), 255) << "id " << id;
      EXPECT_EQ(bitmap.At(i, 9), 255) << "id " << id;
    }
    for (int i = 1; i < kTagGridCells - 1; ++i) {
      // Ring 1: the black border, 8 cells on a side.
      EXPECT_EQ(bitmap.At(1, i), 0) << "id " << id;
      EXPECT_EQ(bitmap.At(8, i), 0) << "id " << id;
      EXPECT_EQ(bitmap.At(i, 1), 0) << "id " << id;
      EXPECT_EQ(bitmap.At(i, 8), 0) << "id " << id;
    }
    std::vector<uint8_t> data;
    int white = 0;
    for (int row = 2; row < 8; ++row) {
      for (int col = 2; col < 8; ++col) {
        const uint8_t v = bitmap.At(row, col);
        EXPECT_TRUE(v == 0 || v == 255);
        white += v == 255;
        data.push_back(v);
      }
    }
    // A 36-bit code is neither all black nor all white.
    EXPECT_GT(white, 0) << "id " << id;
    EXPECT_LT(white, 36) << "id " << id;
    for (const auto& other : data_cells) EXPECT_NE(data, other) << "id " << id;
    data_cells.push_back(data);
  }
}

TEST(ApriltagBitmapTest, ScalesByNearestNeighbour) {
  const TagImage cells = TagBitmap(42, 1);
  const TagImage scaled = TagBitmap(42, 7);
  ASSERT_EQ(scaled.size, 70);
  ASSERT_EQ(scaled.gray.size(), 4900u);
  for (int row = 0; row < scaled.size; ++row) {
    for (int col = 0; col < scaled.size; ++col) {
      ASSERT_EQ(scaled.At(row, col), cells.At(row / 7, col / 7)) << row << ", " << col;
    }
  }
}

TEST(ApriltagBitmapTest, TextureOfAMultipleOfTenIsTheScaledBitmapInRgb) {
  const std::vector<uint8_t> rgb = TagTextureRgb(7, 200);
  const TagImage reference = TagBitmap(7, 20);
  ASSERT_EQ(rgb.size(), 200u * 200u * 3u);
  for (int row = 0; row < 200; ++row) {
    for (int col = 0; col < 200; ++col) {
      const size_t texel = (static_cast<size_t>(row) * 200 + col) * 3;
      ASSERT_EQ(rgb[texel], reference.At(row, col)) << row << ", " << col;
      ASSERT_EQ(rgb[texel + 1], rgb[texel]);
      ASSERT_EQ(rgb[texel + 2], rgb[texel]);
    }
  }
  EXPECT_DOUBLE_EQ(TagBlackSideFraction(200), 0.8);
}

TEST(ApriltagBitmapTest, TextureLeftoverTexelsWidenTheQuietZone) {
  // 207 = 10 cells of 20 texels + 7 left over: 3 extra white texels top/left, 4 bottom/right.
  const int size = 207;
  const std::vector<uint8_t> rgb = TagTextureRgb(311, size);
  const TagImage reference = TagBitmap(311, 20);
  ASSERT_EQ(rgb.size(), static_cast<size_t>(size) * size * 3);
  for (int row = 0; row < size; ++row) {
    for (int col = 0; col < size; ++col) {
      const uint8_t texel = rgb[(static_cast<size_t>(row) * size + col) * 3];
      const int r = row - 3, c = col - 3;
      const uint8_t expected =
          (r >= 0 && r < 200 && c >= 0 && c < 200) ? reference.At(r, c) : uint8_t{255};
      ASSERT_EQ(texel, expected) << row << ", " << col;
    }
  }
  EXPECT_DOUBLE_EQ(TagBlackSideFraction(size), 160.0 / 207.0);
  // The smallest texture: one texel per cell.
  EXPECT_EQ(TagTextureRgb(0, 10).size(), 300u);
}

TEST(ApriltagBitmapTest, RejectsBadArguments) {
  EXPECT_THROW(TagBitmap(-1, 1), UserError);
  EXPECT_THROW(TagBitmap(kTag36h11Count, 1), UserError);
  EXPECT_THROW(TagBitmap(0, 0), UserError);
  EXPECT_THROW(TagTextureRgb(0, 9), UserError);
  EXPECT_THROW(TagTextureRgb(587, 100), UserError);
  EXPECT_THROW(TagBlackSideFraction(5), UserError);
}

}  // namespace
}  // namespace recon::worlds
