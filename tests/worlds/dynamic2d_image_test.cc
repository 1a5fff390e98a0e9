// The Dynamic 2D image against the rules of REFERENCE.md section 2.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/worlds/dynamic2d.h"
#include "tests/worlds/reference_image.h"

namespace recon::worlds {
namespace {

using testing::ExpectedImage;

constexpr int kRed = 0, kGreen = 1, kBlue = 2;

float Pixel(const std::vector<float>& image, int c, int a, int b) {
  return image[c * 1024 + a * 32 + b];
}

// A background whose value tells where it is (and is never 255 or 0, so every write shows up).
std::vector<float> PatternBackground() {
  std::vector<float> bg(3 * 32 * 32);
  for (size_t i = 0; i < bg.size(); ++i) bg[i] = 225.0f + static_cast<float>(i % 29);
  return bg;
}

// Items at NaN are not drawn, so only the items a test places are visible.
Dynamic2DState EmptyState() {
  Dynamic2DState s;
  s.robot = {NAN, NAN};
  for (Vec2& p : s.objects) p = {NAN, NAN};
  s.colours = {5, 0, 5, 10};
  s.red = 3;
  return s;
}

int CountDifferences(const std::vector<float>& a, const std::vector<float>& b) {
  int n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

TEST(Dynamic2DImage, MatchesSpecPixelForPixelThroughAnEpisode) {
  for (uint64_t seed : {7u, 8u, 123u}) {
    Dynamic2D world({});
    world.Reset(seed);
    const std::vector<float> background = world.background();
    for (int t = 0; t <= world.EpisodeLength(); ++t) {
      const std::vector<float> y = world.Observe().y;
      ASSERT_EQ(y.size(), 3072u);
      const std::vector<float> expected = ExpectedImage(world.state(), background);
      for (size_t i = 0; i < y.size(); ++i) {
        ASSERT_EQ(y[i], expected[i]) << "seed " << seed << " step " << t << " value " << i;
      }
      if (t < world.EpisodeLength()) world.Step(world.ExpertAction());
    }
    // Kept for the whole episode, not redrawn per step.
    EXPECT_EQ(world.background(), background);
  }
}

TEST(Dynamic2DImage, ItemsAreVisibleInAnEpisodeImage) {
  Dynamic2D world({});
  world.Reset(7);
  const std::vector<float> y = world.Observe().y;
  // Each of the four objects and the robot changes 4 pixels in 2-3 channels, and none overlap at
  // the start (objects are 10 units apart on the circle, the robot is at the centre).
  EXPECT_GE(CountDifferences(y, world.background()), 5 * 4 * 2);
  EXPECT_EQ(Pixel(y, kRed, 15, 15), 0.0f);  // robot at (0, 0): index 16, block {15, 16}
  EXPECT_EQ(Pixel(y, kGreen, 16, 16), 0.0f);
  EXPECT_EQ(Pixel(y, kBlue, 16, 16), Pixel(world.background(), kBlue, 16, 16));
}

TEST(Dynamic2DImage, BackgroundIsIntegersIn225To255CoveringTheRange) {
  Dynamic2D world({});
  world.Reset(3);
  double sum = 0.0;
  float lo = 1e9f, hi = -1e9f;
  for (float v : world.background()) {
    ASSERT_EQ(v, std::floor(v));
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
  }
  EXPECT_EQ(lo, 225.0f);
  EXPECT_EQ(hi, 255.0f);
  EXPECT_NEAR(sum / world.background().size(), 240.0, 0.5);
  world.Reset(4);
  EXPECT_GT(CountDifferences(world.background(), Dynamic2D(Dynamic2DOptions{}).background()), 2000);
}

TEST(Dynamic2DImage, PixelIndexRoundsHalfToEven) {
  EXPECT_EQ(Dynamic2D::PixelIndex(0.0), 16);
  EXPECT_EQ(Dynamic2D::PixelIndex(0.375), 16);   // 16.5 -> 16 (half away from zero gives 17)
  EXPECT_EQ(Dynamic2D::PixelIndex(1.125), 18);   // 17.5 -> 18
  EXPECT_EQ(Dynamic2D::PixelIndex(-0.375), 16);  // 15.5 -> 16
  EXPECT_EQ(Dynamic2D::PixelIndex(-1.125), 14);  // 14.5 -> 14
  EXPECT_EQ(Dynamic2D::PixelIndex(0.4), 17);     // 16.53 -> 17
  EXPECT_EQ(Dynamic2D::PixelIndex(-12.0), 0);
  EXPECT_EQ(Dynamic2D::PixelIndex(12.0), 32);
}

TEST(Dynamic2DImage, HandPlacedItemsLandOnTheRightPixels) {
  // Half-way cases: 14.5 and 16.5 round to 14 and 16 (half away from zero would give 15 and 17).
  Dynamic2DState s = EmptyState();
  s.objects[3] = {-1.125, 0.375};  // red: x 14.5 -> 14, rows {13, 14}; y 16.5 -> 16, cols {15, 16}
  s.robot = {-6.0, 3.0};           // x index 8 -> rows {7, 8}; y index 20 -> cols {19, 20}
  s.objects[0] = {0.375, 6.0};     // olive: x 16.5 -> 16, rows {15, 16}; y 24 -> cols {23, 24}
  const std::vector<float> bg = PatternBackground();
  const std::vector<float> image = Dynamic2D::RenderImage(s, bg);

  for (int a : {13, 14}) {
    for (int b : {15, 16}) {
      EXPECT_EQ(Pixel(image, kRed, a, b), 255.0f);
      EXPECT_EQ(Pixel(image, kGreen, a, b), 0.0f);
      EXPECT_EQ(Pixel(image, kBlue, a, b), 0.0f);
    }
  }
  for (int a : {7, 8}) {
    for (int b : {19, 20}) {
      EXPECT_EQ(Pixel(image, kRed, a, b), 0.0f);
      EXPECT_EQ(Pixel(image, kGreen, a, b), 0.0f);
      EXPECT_EQ(Pixel(image, kBlue, a, b), Pixel(bg, kBlue, a, b));
    }
  }
  for (int a : {15, 16}) {
    for (int b : {23, 24}) {
      EXPECT_EQ(Pixel(image, kRed, a, b), 127.5f);
      EXPECT_EQ(Pixel(image, kGreen, a, b), 127.5f);
      EXPECT_EQ(Pixel(image, kBlue, a, b), 0.0f);
    }
  }
  // Where rounding half up would have put the blocks: these must stay background.
  EXPECT_EQ(Pixel(image, kRed, 15, 15), Pixel(bg, kRed, 15, 15));
  EXPECT_EQ(Pixel(image, kRed, 13, 17), Pixel(bg, kRed, 13, 17));
  EXPECT_EQ(Pixel(image, kRed, 17, 23), Pixel(bg, kRed, 17, 23));
  // Nothing else changed: 3 items x 4 pixels, 2 channels for the robot and 3 for the objects.
  EXPECT_EQ(CountDifferences(image, bg), 4 * 2 + 2 * 4 * 3);
  EXPECT_EQ(image, ExpectedImage(s, bg));
}

TEST(Dynamic2DImage, ObjectsOverwriteTheRobotAndLaterObjectsEarlierOnes) {
  Dynamic2DState s = EmptyState();
  s.robot = {0.0, 0.0};
  s.objects[1] = {0.0, 0.0};  // green, on the robot
  s.objects[3] = {0.9, 0.0};  // red, index 17 -> rows {16, 17}: overlaps row 16 of the green one
  const std::vector<float> bg = PatternBackground();
  const std::vector<float> image = Dynamic2D::RenderImage(s, bg);
  EXPECT_EQ(Pixel(image, kGreen, 15, 15), 255.0f);  // green object over the robot
  EXPECT_EQ(Pixel(image, kBlue, 15, 15), 0.0f);
  EXPECT_EQ(Pixel(image, kRed, 16, 15), 255.0f);  // red object (drawn later) over the green one
  EXPECT_EQ(Pixel(image, kGreen, 16, 15), 0.0f);
  EXPECT_EQ(image, ExpectedImage(s, bg));
}

TEST(Dynamic2DImage, BlocksAreClippedAtTheBorder) {
  const std::vector<float> bg = PatternBackground();
  Dynamic2DState s = EmptyState();
  s.objects[3] = {-12.0, 12.0};  // indices 0 and 32: blocks {-1, 0} and {31, 32}
  std::vector<float> image = Dynamic2D::RenderImage(s, bg);
  EXPECT_EQ(Pixel(image, kRed, 0, 31), 255.0f);
  EXPECT_EQ(Pixel(image, kRed, 1, 31), Pixel(bg, kRed, 1, 31));
  EXPECT_EQ(Pixel(image, kRed, 0, 30), Pixel(bg, kRed, 0, 30));
  EXPECT_EQ(CountDifferences(image, bg), 1 * 3);
  EXPECT_EQ(image, ExpectedImage(s, bg));

  s.objects[3] = {-11.625, 11.25};  // 0.5 -> 0 (even): block {0}; index 31: block {30, 31}
  image = Dynamic2D::RenderImage(s, bg);
  EXPECT_EQ(Pixel(image, kRed, 0, 30), 255.0f);
  EXPECT_EQ(Pixel(image, kRed, 0, 31), 255.0f);
  EXPECT_EQ(CountDifferences(image, bg), 2 * 3);

  // Far outside the view the clipped indices pin the item to the border (docs/worlds.md).
  s.objects[3] = {40.0, -40.0};
  image = Dynamic2D::RenderImage(s, bg);
  EXPECT_EQ(Pixel(image, kRed, 31, 0), 255.0f);
  EXPECT_EQ(CountDifferences(image, bg), 1 * 3);
  EXPECT_EQ(image, ExpectedImage(s, bg));
}

TEST(Dynamic2DImage, StateObservationIsTheFourteenVector) {
  Dynamic2DOptions options;
  options.observation = "state";
  Dynamic2D world(options);
  world.Reset(11);
  world.Step({0.5f, -0.25f});
  const std::vector<float> y = world.Observe().y;
  ASSERT_EQ(y.size(), 14u);
  const Dynamic2DState& s = world.state();
  EXPECT_FLOAT_EQ(y[0], 0.5f);
  EXPECT_FLOAT_EQ(y[1], -0.25f);
  for (int i = 0; i < 4; ++i) {
    EXPECT_FLOAT_EQ(y[2 + 2 * i], static_cast<float>(s.objects[i][0]));
    EXPECT_FLOAT_EQ(y[3 + 2 * i], static_cast<float>(s.objects[i][1]));
    EXPECT_FLOAT_EQ(y[10 + i], static_cast<float>(s.colours[i]));
  }
  EXPECT_EQ(world.Spec().y_shape, (std::vector<int64_t>{14}));
}

}  // namespace
}  // namespace recon::worlds
