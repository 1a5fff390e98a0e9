// Random-shift augmentation (DrQ) and random erasing (cutout): the image operations, their
// draws, and training with them.

#include "engine/learn/augmentation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::HasSubstr;

// A 2-channel 3 x 4 image whose value names its place: 100 c + 10 r + k.
std::vector<float> NamedImage() {
  std::vector<float> image;
  for (int c = 0; c < 2; ++c) {
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 4; ++k) image.push_back(static_cast<float>(100 * c + 10 * r + k));
    }
  }
  return image;
}

float At(const std::vector<float>& image, int c, int r, int k) {
  return image[(c * 3 + r) * 4 + k];
}

TEST(AugmentationTest, ShiftMovesThePixelsAndReplicatesTheBorder) {
  const std::vector<float> image = NamedImage();
  std::vector<float> out(image.size());
  ShiftImage(image.data(), 2, 3, 4, 0, 0, out.data());
  EXPECT_EQ(out, image);
  for (int dy = -4; dy <= 4; ++dy) {
    for (int dx = -5; dx <= 5; ++dx) {
      ShiftImage(image.data(), 2, 3, 4, dy, dx, out.data());
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 3; ++r) {
          for (int k = 0; k < 4; ++k) {
            const int sr = std::clamp(r + dy, 0, 2), sk = std::clamp(k + dx, 0, 3);
            ASSERT_EQ(At(out, c, r, k), 100 * c + 10 * sr + sk)
                << "shift " << dy << "," << dx << " at " << c << "," << r << "," << k;
          }
        }
      }
    }
  }
}

TEST(AugmentationTest, DrawsCoverTheRangeAndRepeatFromTheSeed) {
  Rng a(5), b(5);  // seed 5
  std::vector<int> seen(9, 0);
  for (int i = 0; i < 2000; ++i) {
    const Shift s = DrawShift(a, 4);
    const Shift t = DrawShift(b, 4);
    ASSERT_EQ(s.dy, t.dy);
    ASSERT_EQ(s.dx, t.dx);
    ASSERT_GE(s.dy, -4);
    ASSERT_LE(s.dy, 4);
    ASSERT_GE(s.dx, -4);
    ASSERT_LE(s.dx, 4);
    ++seen[s.dx + 4];
  }
  for (int count : seen) EXPECT_GT(count, 150);  // about 222 each
}

TrainConfig ShiftConfig(int shift) {
  TrainConfig train;
  train.steps = 60;
  train.seed = 9;
  train.random_shift_px = shift;
  return train;
}

TEST(AugmentationTest, TrainingWithShiftsIsReproducibleAndDiffersFromWithout) {
  const Dataset data = testing::MakeImageTask(11, 24, 16, 6);
  auto run = [&](const TrainConfig& train) {
    Trainer trainer(data, testing::SmallImageNet(), train);
    trainer.Train();
    return testing::Probe(trainer.policy(), data);
  };
  const std::vector<float> shifted = run(ShiftConfig(2));
  EXPECT_TRUE(testing::BitwiseEqual(shifted, run(ShiftConfig(2))));
  EXPECT_FALSE(testing::BitwiseEqual(shifted, run(ShiftConfig(0))));
  EXPECT_FALSE(testing::BitwiseEqual(shifted, run(ShiftConfig(3))));
}

TEST(AugmentationTest, ACheckpointResumesTheShiftsBitwise) {
  EXPECT_TRUE(testing::ResumedRunMatchesUninterrupted(
      testing::MakeImageTask(12, 24, 16, 6), testing::SmallImageNet(), ShiftConfig(3),
      ::testing::TempDir() + "/recon_augment_resume.ckpt"));
}

TEST(AugmentationTest, TheSettingIsStoredAndBadValuesAreRefused) {
  TrainConfig train = ShiftConfig(4);
  EXPECT_EQ(TrainConfigFromJson(ToJson(train)).random_shift_px, 4);
  nlohmann::json j = nlohmann::json::parse(ToJson(train));
  j.erase("random_shift_px");  // as written before the setting existed
  EXPECT_EQ(TrainConfigFromJson(j.dump()).random_shift_px, 0);

  const Dataset images = testing::MakeImageTask(13, 8, 16);
  for (int bad : {-1, kMaxRandomShiftPx + 1}) {
    try {
      Trainer trainer(images, testing::SmallImageNet(), ShiftConfig(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("random_shift_px must be between 0 and 16"));
    }
  }
  try {
    Trainer trainer(testing::MakeVectorTask(3, 4), NetworkConfig{}, ShiftConfig(2));
    ADD_FAILURE() << "shifted a vector";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("y is a vector"));
  }
}

TEST(AugmentationTest, ErasePaintsTheSquareWithEachChannelsMeanAndLeavesTheRest) {
  const std::vector<float> image = NamedImage();
  // Channel means of the named image: 100 c + 10 * 1 (rows 0-2) + 1.5 (columns 0-3).
  const float means[2] = {11.5f, 111.5f};
  for (int side = 0; side <= 3; ++side) {
    for (int row = 0; row + side <= 3; ++row) {
      for (int col = 0; col + side <= 4; ++col) {
        std::vector<float> out = image;
        EraseSquare(out.data(), 2, 3, 4, Erase{row, col, side});
        for (int c = 0; c < 2; ++c) {
          for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 4; ++k) {
              const bool inside = r >= row && r < row + side && k >= col && k < col + side;
              ASSERT_EQ(At(out, c, r, k), inside ? means[c] : At(image, c, r, k))
                  << "square " << row << "," << col << " side " << side << " at " << c << "," << r
                  << "," << k;
            }
          }
        }
      }
    }
  }
}

TEST(AugmentationTest, EraseDrawsKeepTheSquareInsideAndRepeatFromTheSeed) {
  Rng a(21), b(21);
  std::vector<int> rows(4, 0), cols(7, 0);
  for (int i = 0; i < 2000; ++i) {
    const Erase e = DrawErase(a, 6, 9, 3);
    const Erase f = DrawErase(b, 6, 9, 3);
    ASSERT_EQ(e.row, f.row);
    ASSERT_EQ(e.col, f.col);
    ASSERT_EQ(e.side, 3);
    ASSERT_GE(e.row, 0);
    ASSERT_LE(e.row + e.side, 6);
    ASSERT_GE(e.col, 0);
    ASSERT_LE(e.col + e.side, 9);
    ++rows[e.row];
    ++cols[e.col];
  }
  for (int count : rows) EXPECT_GT(count, 400);  // about 500 each
  for (int count : cols) EXPECT_GT(count, 230);  // about 286 each
  // A square larger than the image covers all of it.
  const Erase whole = DrawErase(a, 6, 9, 20);
  EXPECT_EQ(whole.side, 6);
  EXPECT_EQ(whole.row, 0);
  EXPECT_GE(whole.col, 0);
  EXPECT_LE(whole.col, 3);
}

TrainConfig EraseConfig(int side) {
  TrainConfig train = ShiftConfig(0);
  train.random_erase_px = side;
  return train;
}

TEST(AugmentationTest, TrainingWithErasingIsReproducibleAndDiffersFromWithout) {
  const Dataset data = testing::MakeImageTask(14, 24, 16, 6);
  auto run = [&](const TrainConfig& train) {
    Trainer trainer(data, testing::SmallImageNet(), train);
    trainer.Train();
    return testing::Probe(trainer.policy(), data);
  };
  const std::vector<float> erased = run(EraseConfig(5));
  EXPECT_TRUE(testing::BitwiseEqual(erased, run(EraseConfig(5))));
  EXPECT_FALSE(testing::BitwiseEqual(erased, run(EraseConfig(0))));
  EXPECT_FALSE(testing::BitwiseEqual(erased, run(EraseConfig(8))));
  TrainConfig both = EraseConfig(5);
  both.random_shift_px = 2;
  EXPECT_FALSE(testing::BitwiseEqual(erased, run(both)));
  // The dataset's own images are never painted: training again from it gives the same result.
  EXPECT_TRUE(testing::BitwiseEqual(erased, run(EraseConfig(5))));
}

TEST(AugmentationTest, ACheckpointResumesTheErasingBitwise) {
  TrainConfig train = EraseConfig(4);
  train.random_shift_px = 1;
  EXPECT_TRUE(testing::ResumedRunMatchesUninterrupted(
      testing::MakeImageTask(15, 24, 16, 6), testing::SmallImageNet(), train,
      ::testing::TempDir() + "/recon_erase_resume.ckpt"));
}

TEST(AugmentationTest, TheErasingIsStoredAndBadValuesAreRefused) {
  EXPECT_EQ(TrainConfigFromJson(ToJson(EraseConfig(6))).random_erase_px, 6);
  nlohmann::json j = nlohmann::json::parse(ToJson(EraseConfig(6)));
  j.erase("random_erase_px");  // as written before the setting existed
  EXPECT_EQ(TrainConfigFromJson(j.dump()).random_erase_px, 0);

  const Dataset images = testing::MakeImageTask(13, 8, 16);
  for (int bad : {-1, kMaxRandomErasePx + 1}) {
    try {
      Trainer trainer(images, testing::SmallImageNet(), EraseConfig(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("random_erase_px must be between 0 and 64"));
    }
  }
  try {
    Trainer trainer(testing::MakeVectorTask(3, 4), NetworkConfig{}, EraseConfig(2));
    ADD_FAILURE() << "erased a vector";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("random_erase_px erases squares of camera images"));
  }
}

}  // namespace
}  // namespace recon::learn
