#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/report/bar_layout.h"
#include "engine/report/chart.h"
#include "tests/report/test_support.h"

namespace recon::report {
namespace {

using testing::PaperBarChart;
using testing::PngImage;
using testing::ScratchDir;

TEST(BarChartTest, PngHasRequestedSizeAndBarColoursAtBarCentres) {
  ScratchDir dir("bar_png");
  const BarChart chart = PaperBarChart();
  const std::string path = dir.File("bars.png");
  WriteChart(chart, path, 960, 540);

  const PngImage image(path);
  EXPECT_EQ(image.width(), 960);
  EXPECT_EQ(image.height(), 540);
  // Anti-aliased text, bars and lines give far more than a handful of colours.
  EXPECT_GT(image.DistinctColors(), 100u);

  const BarLayout layout = LayoutBarChart(chart, 960, 540);
  ASSERT_EQ(layout.center_x.size(), chart.values.size());
  for (size_t i = 0; i < chart.values.size(); ++i) {
    // 60% of the way up the bar: clear of the whisker and of the reference lines.
    const double value = layout.baseline + 0.6 * (chart.values[i] - layout.baseline);
    const double y = layout.axis.ToPixel(value, layout.plot);
    EXPECT_TRUE(PngImage::Near(image.Rgb(layout.center_x[i], y), PaletteColor(i), 2))
        << "bar " << i << " at (" << layout.center_x[i] << ", " << y << ") is #" << std::hex
        << image.Rgb(layout.center_x[i], y);
  }
}

TEST(BarChartTest, WhiskersRiseAboveTheBarTop) {
  ScratchDir dir("whiskers");
  const BarChart chart = PaperBarChart();
  const std::string path = dir.File("bars.png");
  WriteChart(chart, path);
  const PngImage image(path);
  const BarLayout layout = LayoutBarChart(chart, 960, 540);
  auto dark = [](uint32_t rgb) {
    return ((rgb >> 16) & 0xFF) < 90 && ((rgb >> 8) & 0xFF) < 90 && (rgb & 0xFF) < 90;
  };
  for (size_t i = 0; i < chart.values.size(); ++i) {
    const double y = layout.axis.ToPixel(chart.values[i] + chart.errors[i] / 2, layout.plot);
    const double x = layout.center_x[i];
    EXPECT_TRUE(dark(image.Rgb(x, y))) << "no whisker above bar " << i;
    // Beside the whisker, above the bar, is background: the dark pixel is the whisker.
    EXPECT_FALSE(dark(image.Rgb(x + layout.bar_width * 0.45, y))) << "bar " << i;
  }
}

TEST(BarChartTest, ExplicitColoursAreUsed) {
  ScratchDir dir("colours");
  BarChart chart;
  chart.labels = {"a", "b"};
  chart.values = {3, 5};
  const Color magenta{1, 0, 1};
  chart.colors = {magenta, magenta};
  const std::string path = dir.File("bars.png");
  WriteChart(chart, path, 400, 300);
  const PngImage image(path);
  EXPECT_EQ(image.width(), 400);
  EXPECT_EQ(image.height(), 300);
  EXPECT_GT(image.CountNear(magenta, 1), 2000u);
  EXPECT_EQ(image.CountNear(PaletteColor(0), 1), 0u);
}

TEST(BarChartTest, AxisStartsNearTheDataAndCoversWhiskersAndReferences) {
  const BarChart chart = PaperBarChart();
  const BarLayout layout = LayoutBarChart(chart, 960, 540);
  const AxisTicks& ticks = layout.axis.ticks;
  EXPECT_GT(ticks.lo, 0) << "bars far from 0 start at a nice minimum, not at 0";
  EXPECT_LT(ticks.lo, 10.0) << "the 'standing still' reference must be visible";
  EXPECT_GE(ticks.hi, 17.79);
  EXPECT_DOUBLE_EQ(layout.baseline, ticks.lo);
  EXPECT_DOUBLE_EQ(ticks.lo, ticks.values.front());
  EXPECT_DOUBLE_EQ(ticks.hi, ticks.values.back());

  BarChart no_references = chart;
  no_references.references.clear();
  const AxisTicks tight = LayoutBarChart(no_references, 960, 540).axis.ticks;
  EXPECT_GT(tight.lo, 10.0);
  EXPECT_LE(tight.lo, 13.02 - 0.38);
  EXPECT_GE(tight.hi, 16.82 + 0.28);

  BarChart from_zero = chart;
  from_zero.y_min = 0;
  from_zero.y_max = 20;
  const BarLayout fixed = LayoutBarChart(from_zero, 960, 540);
  EXPECT_DOUBLE_EQ(fixed.axis.ticks.lo, 0);
  EXPECT_DOUBLE_EQ(fixed.axis.ticks.hi, 20);
  EXPECT_DOUBLE_EQ(fixed.baseline, 0);
}

TEST(BarChartTest, SmallPositiveValuesStartAtZero) {
  BarChart chart;
  chart.labels = {"a", "b", "c"};
  chart.values = {0.1, 0.5, 0.9};
  chart.errors = {0.05, 0.05, 0.05};
  EXPECT_DOUBLE_EQ(LayoutBarChart(chart, 960, 540).axis.ticks.lo, 0);
}

TEST(BarChartTest, TenLongLabelsDoNotOverlapAt960Pixels) {
  const BarChart chart = PaperBarChart();
  const BarLayout layout = LayoutBarChart(chart, 960, 540);
  ASSERT_EQ(layout.label_lines.size(), 10u);
  Canvas canvas(ImageFormat::kPng, 1, 1);
  const double slot = layout.center_x[1] - layout.center_x[0];
  const double line = canvas.LineHeight(layout.style.bar_label);
  if (layout.label_angle_rad == 0) {
    for (const auto& lines : layout.label_lines) {
      for (const auto& text : lines)
        EXPECT_LT(canvas.TextWidth(text, layout.style.bar_label), slot);
    }
  } else {
    // Parallel rotated labels are slot * sin(angle) apart, which must exceed one line.
    EXPECT_GT(slot * std::sin(layout.label_angle_rad), line);
    for (const auto& lines : layout.label_lines) EXPECT_EQ(lines.size(), 1u);
  }
  // Labels stay inside the image and leave the plot most of it.
  double block = 0;
  for (const auto& lines : layout.label_lines) {
    if (layout.label_angle_rad == 0) {
      block = std::max(block, line * lines.size());
    } else {
      block = std::max(block, canvas.TextWidth(lines[0], layout.style.bar_label) *
                                      std::sin(layout.label_angle_rad) +
                                  line);
    }
  }
  EXPECT_LE(layout.plot.Bottom() + block, 540);
  EXPECT_GT(layout.plot.h, 540 * 0.6);
}

TEST(BarChartTest, ScalesToLargerImages) {
  ScratchDir dir("large");
  const std::string path = dir.File("bars.png");
  WriteChart(PaperBarChart(), path, 1920, 1080);
  const PngImage image(path);
  EXPECT_EQ(image.width(), 1920);
  EXPECT_EQ(image.height(), 1080);
  const BarLayout layout = LayoutBarChart(PaperBarChart(), 1920, 1080);
  EXPECT_DOUBLE_EQ(layout.style.scale, 2.0);
}

TEST(BarChartTest, NegativeValuesHangFromZero) {
  ScratchDir dir("negative");
  BarChart chart;
  chart.labels = {"up", "down"};
  chart.values = {2, -3};
  chart.errors = {0.5, 0.5};
  const BarLayout layout = LayoutBarChart(chart, 960, 540);
  EXPECT_DOUBLE_EQ(layout.baseline, 0);
  EXPECT_LE(layout.axis.ticks.lo, -3.5);
  const std::string path = dir.File("bars.png");
  WriteChart(chart, path);
  const PngImage image(path);
  const double y = layout.axis.ToPixel(-1.5, layout.plot);
  EXPECT_TRUE(PngImage::Near(image.Rgb(layout.center_x[1], y), PaletteColor(1), 2));
}

}  // namespace
}  // namespace recon::report
