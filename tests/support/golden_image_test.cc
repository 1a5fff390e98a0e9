#include "tests/support/golden_image.h"

#include <cairo.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/report/image_png.h"

namespace recon::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Sets or unsets an environment variable for one scope and restores the previous value, so a
/// test neither leaks its setting into the next nor depends on the caller's environment.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value->c_str(), 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

constexpr int kWidth = 40;
constexpr int kHeight = 30;
constexpr int64_t kPixels = int64_t{kWidth} * kHeight;

/// A smooth pattern whose channels stay within 20..200, so +-50 never clips and the expected
/// differences are exactly what a test adds.
RgbImage Pattern() {
  RgbImage image;
  image.width = kWidth;
  image.height = kHeight;
  image.rgb.resize(kPixels * 3);
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) {
      uint8_t* px = image.rgb.data() + (r * kWidth + c) * 3;
      px[0] = static_cast<uint8_t>(20 + c * 4);
      px[1] = static_cast<uint8_t>(20 + r * 5);
      px[2] = static_cast<uint8_t>(20 + (r + c) * 2);
    }
  }
  return image;
}

RgbImage Solid(int width, int height, uint8_t value) {
  RgbImage image;
  image.width = width;
  image.height = height;
  image.rgb.assign(static_cast<size_t>(width) * height * 3, value);
  return image;
}

uint8_t* MutablePixel(RgbImage& image, int row, int col) {
  return image.rgb.data() + (static_cast<size_t>(row) * image.width + col) * 3;
}

/// Adds `delta` to `channel` of the pixels in rows [row0, row0 + rows) and columns
/// [col0, col0 + cols).
void Alter(RgbImage& image, int row0, int col0, int rows, int cols, int channel, int delta) {
  for (int r = row0; r < row0 + rows; ++r) {
    for (int c = col0; c < col0 + cols; ++c) {
      uint8_t* px = MutablePixel(image, r, c);
      px[channel] = static_cast<uint8_t>(px[channel] + delta);
    }
  }
}

bool IsRed(const uint8_t* px) { return px[0] >= 128 && px[1] == 0 && px[2] == 0; }

class GoldenImageTest : public ::testing::Test {
 protected:
  GoldenImageTest()
      : dir_(fs::temp_directory_path() /
             ("recon_golden_" +
              std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
              std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    options_.failure_dir = File("failures");
  }
  ~GoldenImageTest() override { fs::remove_all(dir_); }

  std::string File(const std::string& name) const { return (dir_ / name).string(); }

  /// Writes `image` as the golden `<name>.png` and returns its path.
  std::string Golden(const RgbImage& image, const std::string& name = "screen") const {
    const std::string path = File(name + ".png");
    report::WritePng(image, path);
    return path;
  }

  // Whatever the caller's environment says, these tests decide themselves whether goldens are
  // updated and where failures go.
  ScopedEnv update_{"RECON_UPDATE_GOLDENS", std::nullopt};
  ScopedEnv failures_{"RECON_GOLDEN_FAILURES", std::nullopt};
  fs::path dir_;
  GoldenOptions options_;
};

TEST_F(GoldenImageTest, IdenticalImagesMatch) {
  const RgbImage image = Pattern();
  const ImageDifference difference = CompareImages(image, image, 0);
  EXPECT_TRUE(difference.same_size);
  EXPECT_EQ(difference.pixels_over_tolerance, 0);
  EXPECT_EQ(difference.fraction_over_tolerance, 0);
  EXPECT_EQ(difference.max_channel_difference, 0);
  EXPECT_EQ(difference.mean_abs_difference, 0);

  EXPECT_TRUE(MatchesGolden(image, Golden(image), options_));
  // Nothing to look at when nothing failed.
  EXPECT_FALSE(fs::exists(options_.failure_dir + "/screen.actual.png"));
}

TEST_F(GoldenImageTest, AlteredRegionBeyondToleranceFailsWithItsCounts) {
  const RgbImage golden = Pattern();
  RgbImage actual = golden;
  Alter(actual, 10, 12, 4, 5, /*channel=*/0, 50);  // 20 pixels, red +50

  const ImageDifference difference = CompareImages(golden, actual, 8);
  EXPECT_EQ(difference.pixels_over_tolerance, 20);
  EXPECT_DOUBLE_EQ(difference.fraction_over_tolerance, 20.0 / kPixels);
  EXPECT_EQ(difference.max_channel_difference, 50);
  EXPECT_DOUBLE_EQ(difference.mean_abs_difference, 20.0 * 50 / (kPixels * 3));

  const ::testing::AssertionResult result = MatchesGolden(actual, Golden(golden), options_);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr("20 of 1200 pixels (1.667 %)"));
  EXPECT_THAT(result.message(), HasSubstr("more than 8"));
  EXPECT_THAT(result.message(), HasSubstr("largest channel difference 50"));
  EXPECT_THAT(result.message(), HasSubstr("mean absolute difference 0.278"));
  EXPECT_THAT(result.message(), HasSubstr("--update-goldens"));
}

TEST_F(GoldenImageTest, ShiftedSquareFailsWithItsEdges) {
  // A 6x6 black square on white moved right by 2: the 2 columns it left and the 2 it entered
  // differ, 2 * 6 * 2 = 24 pixels, all by 255.
  RgbImage golden = Solid(kWidth, kHeight, 255);
  RgbImage actual = golden;
  for (int channel = 0; channel < 3; ++channel) {
    Alter(golden, 5, 5, 6, 6, channel, -255);
    Alter(actual, 5, 7, 6, 6, channel, -255);
  }

  const ImageDifference difference = CompareImages(golden, actual, 8);
  EXPECT_EQ(difference.pixels_over_tolerance, 24);
  EXPECT_EQ(difference.max_channel_difference, 255);
  EXPECT_DOUBLE_EQ(difference.mean_abs_difference, 24.0 * 255 * 3 / (kPixels * 3));
  const ::testing::AssertionResult result = MatchesGolden(actual, Golden(golden), options_);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr("24 of 1200 pixels"));
}

TEST_F(GoldenImageTest, ChangeWithinTolerancePasses) {
  const RgbImage golden = Pattern();
  RgbImage within = golden;
  for (int channel = 0; channel < 3; ++channel) Alter(within, 0, 0, kHeight, kWidth, channel, 8);
  const ImageDifference difference = CompareImages(golden, within, 8);
  EXPECT_EQ(difference.pixels_over_tolerance, 0);
  EXPECT_EQ(difference.max_channel_difference, 8);
  EXPECT_DOUBLE_EQ(difference.mean_abs_difference, 8);
  const std::string golden_path = Golden(golden);
  EXPECT_TRUE(MatchesGolden(within, golden_path, options_));

  // One more step in one channel is over tolerance, for every pixel.
  RgbImage over = within;
  Alter(over, 0, 0, kHeight, kWidth, 1, 1);
  EXPECT_EQ(CompareImages(golden, over, 8).pixels_over_tolerance, kPixels);
  EXPECT_FALSE(MatchesGolden(over, golden_path, options_));
}

TEST_F(GoldenImageTest, AFewPixelsOverToleranceAreAllowed) {
  // 0.2 % of 1200 pixels is 2.4: two stray pixels pass, three fail.
  const RgbImage golden = Pattern();
  const std::string golden_path = Golden(golden);
  RgbImage actual = golden;
  Alter(actual, 0, 0, 1, 2, 2, 40);
  EXPECT_TRUE(MatchesGolden(actual, golden_path, options_));
  Alter(actual, 29, 39, 1, 1, 2, 40);
  const ::testing::AssertionResult result = MatchesGolden(actual, golden_path, options_);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr("3 of 1200 pixels (0.250 %)"));
  EXPECT_THAT(result.message(), HasSubstr("at most 0.200 %"));
}

TEST_F(GoldenImageTest, DifferentSizesFail) {
  const RgbImage golden = Solid(kWidth, kHeight, 100);
  const RgbImage actual = Solid(kWidth + 1, kHeight, 100);
  const ImageDifference difference = CompareImages(golden, actual, 8);
  EXPECT_FALSE(difference.same_size);
  EXPECT_EQ(difference.width_a, kWidth);
  EXPECT_EQ(difference.width_b, kWidth + 1);
  EXPECT_EQ(difference.fraction_over_tolerance, 1.0);

  const ::testing::AssertionResult result = MatchesGolden(actual, Golden(golden), options_);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr("the actual image is 41x30 but golden"));
  EXPECT_THAT(result.message(), HasSubstr("is 40x30"));
  // The diff covers both; only the extra column is red.
  const RgbImage diff = ReadPng(options_.failure_dir + "/screen.diff.png");
  ASSERT_EQ(diff.width, kWidth + 1);
  ASSERT_EQ(diff.height, kHeight);
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth + 1; ++c) {
      EXPECT_EQ(IsRed(diff.Pixel(r, c)), c == kWidth) << "row " << r << " col " << c;
    }
  }
}

TEST_F(GoldenImageTest, FailureWritesActualAndDiffMarkingExactlyTheAlteredPixels) {
  const RgbImage golden = Pattern();
  RgbImage actual = golden;
  Alter(actual, 3, 4, 2, 3, 1, 30);     // rows 3-4, columns 4-6
  Alter(actual, 20, 30, 5, 1, 2, -20);  // rows 20-24, column 30
  Alter(actual, 0, 0, 1, 1, 0, 5);      // within tolerance: must stay grey

  const ::testing::AssertionResult result = MatchesGolden(actual, Golden(golden), options_);
  ASSERT_FALSE(result);
  const std::string actual_path = options_.failure_dir + "/screen.actual.png";
  const std::string diff_path = options_.failure_dir + "/screen.diff.png";
  EXPECT_THAT(result.message(), HasSubstr(actual_path));
  EXPECT_THAT(result.message(), HasSubstr(diff_path));

  const RgbImage written = ReadPng(actual_path);
  EXPECT_EQ(written.width, kWidth);
  EXPECT_EQ(written.height, kHeight);
  EXPECT_EQ(written.rgb, actual.rgb);

  const RgbImage diff = ReadPng(diff_path);
  ASSERT_EQ(diff.width, kWidth);
  ASSERT_EQ(diff.height, kHeight);
  int red = 0;
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) {
      const bool altered =
          (r >= 3 && r <= 4 && c >= 4 && c <= 6) || (r >= 20 && r <= 24 && c == 30);
      const uint8_t* px = diff.Pixel(r, c);
      EXPECT_EQ(IsRed(px), altered) << "row " << r << " col " << c;
      if (!altered) {
        EXPECT_TRUE(px[0] == px[1] && px[1] == px[2] && px[0] >= 191)
            << "row " << r << " col " << c;
      }
      red += IsRed(px);
    }
  }
  EXPECT_EQ(red, 6 + 5);
  // Brighter red for the larger difference.
  EXPECT_GT(diff.Pixel(3, 4)[0], diff.Pixel(20, 30)[0]);
}

TEST_F(GoldenImageTest, PassingRemovesStaleFailureImages) {
  const RgbImage golden = Pattern();
  const std::string golden_path = Golden(golden);
  RgbImage actual = golden;
  Alter(actual, 0, 0, 5, 5, 0, 50);
  ASSERT_FALSE(MatchesGolden(actual, golden_path, options_));
  ASSERT_TRUE(fs::exists(options_.failure_dir + "/screen.diff.png"));
  ASSERT_TRUE(MatchesGolden(golden, golden_path, options_));
  EXPECT_FALSE(fs::exists(options_.failure_dir + "/screen.actual.png"));
  EXPECT_FALSE(fs::exists(options_.failure_dir + "/screen.diff.png"));
}

TEST_F(GoldenImageTest, FailureDirDefaultsToTheEnvironment) {
  const ScopedEnv failures("RECON_GOLDEN_FAILURES", File("from-env"));
  const RgbImage golden = Pattern();
  RgbImage actual = golden;
  Alter(actual, 0, 0, 5, 5, 0, 50);
  EXPECT_FALSE(MatchesGolden(actual, Golden(golden), GoldenOptions{}));
  EXPECT_TRUE(fs::exists(File("from-env/screen.actual.png")));
  EXPECT_TRUE(fs::exists(File("from-env/screen.diff.png")));
}

TEST_F(GoldenImageTest, UpdateGoldensCreatesAndRefreshes) {
  const std::string golden_path = File("goldens/app/screen.png");  // folders do not exist yet
  const RgbImage first = Pattern();
  RgbImage second = first;
  Alter(second, 0, 0, kHeight, kWidth, 0, 50);
  {
    const ScopedEnv update("RECON_UPDATE_GOLDENS", "1");
    const ::testing::AssertionResult created = MatchesGolden(first, golden_path, options_);
    ASSERT_TRUE(created);
    EXPECT_THAT(created.message(), HasSubstr("created golden " + golden_path));
    EXPECT_EQ(ReadPng(golden_path).rgb, first.rgb);

    const ::testing::AssertionResult refreshed = MatchesGolden(second, golden_path, options_);
    ASSERT_TRUE(refreshed);
    EXPECT_THAT(refreshed.message(), HasSubstr("refreshed golden " + golden_path));
    EXPECT_EQ(ReadPng(golden_path).rgb, second.rgb);
  }
  // Back to comparing: the refreshed golden is the reference now.
  EXPECT_TRUE(MatchesGolden(second, golden_path, options_));
  EXPECT_FALSE(MatchesGolden(first, golden_path, options_));
}

TEST_F(GoldenImageTest, OnlyOneUpdatesGoldens) {
  const ScopedEnv update("RECON_UPDATE_GOLDENS", "0");
  EXPECT_FALSE(MatchesGolden(Pattern(), File("absent.png"), options_));
  EXPECT_FALSE(fs::exists(File("absent.png")));
}

TEST_F(GoldenImageTest, MissingGoldenFailsSayingHowToCreateIt) {
  const std::string golden_path = File("absent.png");
  const ::testing::AssertionResult result = MatchesGolden(Pattern(), golden_path, options_);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr(golden_path + " does not exist"));
  EXPECT_THAT(result.message(), HasSubstr("run the test with --update-goldens"));
  EXPECT_THAT(result.message(), HasSubstr("RECON_UPDATE_GOLDENS=1"));
  EXPECT_FALSE(fs::exists(golden_path));
  // The image is kept so it can be reviewed before it becomes the golden; there is no diff.
  EXPECT_EQ(ReadPng(options_.failure_dir + "/absent.actual.png").rgb, Pattern().rgb);
  EXPECT_FALSE(fs::exists(options_.failure_dir + "/absent.diff.png"));
}

TEST_F(GoldenImageTest, CorruptGoldenFailsRatherThanThrows) {
  const std::string golden_path = File("corrupt.png");
  std::ofstream(golden_path) << "not a png";
  const ::testing::AssertionResult result = MatchesGolden(Pattern(), golden_path, options_);
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr(golden_path));
  EXPECT_THAT(result.message(), HasSubstr("--update-goldens"));
}

TEST_F(GoldenImageTest, ReadPngOfNonPngThrowsNamingIt) {
  const std::string text = File("notes.png");
  std::ofstream(text) << "these are notes, not pixels\n";
  try {
    ReadPng(text);
    FAIL() << "no exception";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr(text));
    EXPECT_THAT(e.what(), HasSubstr("not a PNG"));
  }
  try {
    ReadPng(File("missing.png"));
    FAIL() << "no exception";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr(File("missing.png")));
    EXPECT_THAT(e.what(), HasSubstr("no such file"));
  }
}

TEST_F(GoldenImageTest, ReadPngRoundTripsAndDropsAlpha) {
  const RgbImage image = Pattern();
  EXPECT_EQ(ReadPng(Golden(image)).rgb, image.rgb);

  // A half-transparent orange pixel reads back as orange, not orange darkened by its alpha.
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 2, 1);
  cairo_t* cr = cairo_create(surface);
  cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
  cairo_set_source_rgba(cr, 1.0, 0.5, 0.0, 0.5);
  cairo_paint(cr);
  cairo_destroy(cr);
  const std::string path = File("alpha.png");
  ASSERT_EQ(cairo_surface_write_to_png(surface, path.c_str()), CAIRO_STATUS_SUCCESS);
  cairo_surface_destroy(surface);
  const RgbImage read = ReadPng(path);
  ASSERT_EQ(read.width, 2);
  ASSERT_EQ(read.height, 1);
  EXPECT_NEAR(read.Pixel(0, 1)[0], 255, 2);
  EXPECT_NEAR(read.Pixel(0, 1)[1], 128, 2);
  EXPECT_NEAR(read.Pixel(0, 1)[2], 0, 2);
}

TEST_F(GoldenImageTest, BadArgumentsThrow) {
  const RgbImage image = Pattern();
  EXPECT_THROW(CompareImages(image, image, -1), std::invalid_argument);
  EXPECT_THROW(CompareImages(image, image, 256), std::invalid_argument);
  RgbImage broken = image;
  broken.rgb.pop_back();
  EXPECT_THROW(CompareImages(image, broken, 8), std::invalid_argument);
  GoldenOptions options = options_;
  options.max_fraction_over_tolerance = 1.5;
  EXPECT_THROW(MatchesGolden(image, Golden(image), options), std::invalid_argument);
}

TEST_F(GoldenImageTest, ParseGoldenFlagsTurnsTheFlagIntoTheVariable) {
  std::vector<std::string> words = {"ui_test", "--gtest_filter=Main.*", "--update-goldens",
                                    "extra"};
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  int argc = 4;
  ParseGoldenFlags(&argc, argv.data());
  ASSERT_EQ(argc, 3);
  EXPECT_STREQ(argv[0], "ui_test");
  EXPECT_STREQ(argv[1], "--gtest_filter=Main.*");
  EXPECT_STREQ(argv[2], "extra");
  EXPECT_EQ(argv[3], nullptr);
  ASSERT_NE(std::getenv("RECON_UPDATE_GOLDENS"), nullptr);
  EXPECT_STREQ(std::getenv("RECON_UPDATE_GOLDENS"), "1");
}

TEST_F(GoldenImageTest, ParseGoldenFlagsLeavesOtherCommandLinesAlone) {
  std::vector<std::string> words = {"ui_test", "--update-goldens-please"};
  std::vector<char*> argv = {words[0].data(), words[1].data(), nullptr};
  int argc = 2;
  ParseGoldenFlags(&argc, argv.data());
  EXPECT_EQ(argc, 2);
  EXPECT_STREQ(argv[1], "--update-goldens-please");
  EXPECT_EQ(std::getenv("RECON_UPDATE_GOLDENS"), nullptr);
}

}  // namespace
}  // namespace recon::testing
