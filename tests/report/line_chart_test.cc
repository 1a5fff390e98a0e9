#include <gtest/gtest.h>

#include <cmath>

#include "engine/report/chart.h"
#include "tests/report/test_support.h"

namespace recon::report {
namespace {

using testing::PngImage;
using testing::ScratchDir;

LineChart::Series Curve(const std::string& name, int points, double scale) {
  LineChart::Series series;
  series.name = name;
  series.markers = false;
  for (int k = 0; k < points; ++k) {
    series.x.push_back(k);
    series.y.push_back(scale * std::exp(-k / 1500.0) + 0.001);
  }
  return series;
}

// Pixel colour of `color` drawn at `alpha` over white.
Color OverWhite(const Color& color, double alpha) {
  return {1 - alpha * (1 - color.r), 1 - alpha * (1 - color.g), 1 - alpha * (1 - color.b)};
}

TEST(LineChartTest, LogYWithNonPositiveValuesDrawsTheRest) {
  ScratchDir dir("log_y");
  LineChart chart;
  chart.title = "loss";
  chart.log_y = true;
  LineChart::Series series = Curve("train", 6000, 2.0);
  series.y[10] = 0;
  series.y[500] = -1;
  series.errors.assign(series.y.size(), 0.5);  // band lower edges go below zero
  chart.series.push_back(series);
  LineChart::Series hopeless;
  hopeless.name = "all non-positive";
  hopeless.x = {0, 1, 2};
  hopeless.y = {0, -1, -2};
  chart.series.push_back(hopeless);
  chart.references = {{0.01, "target"}, {-1, "cannot show on log"}};
  const std::string path = dir.File("loss.png");
  WriteChart(chart, path);
  const PngImage image(path);
  EXPECT_GT(image.CountTinted(PaletteColor(0), 0.5), 600u);
}

TEST(LineChartTest, LogYWithOnlyNonPositiveValuesStillWrites) {
  ScratchDir dir("log_y_empty");
  LineChart chart;
  chart.log_y = true;
  LineChart::Series series;
  series.x = {0, 1};
  series.y = {0, -5};
  chart.series.push_back(series);
  const std::string path = dir.File("loss.png");
  WriteChart(chart, path);
  EXPECT_EQ(PngImage(path).width(), 960);
}

TEST(LineChartTest, ThreeLossCurvesOf6000PointsWithoutMarkers) {
  ScratchDir dir("loss");
  LineChart chart;
  chart.title = "Training loss";
  chart.x_label = "step";
  chart.y_label = "loss";
  chart.log_y = true;
  chart.series = {Curve("RECON", 6000, 3), Curve("Baseline", 6000, 1), Curve("BC", 6000, 0.3)};
  const std::string path = dir.File("loss.png");
  WriteChart(chart, path, 960, 540);
  const PngImage image(path);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(image.CountTinted(PaletteColor(i), 0.5), 600u) << "series " << i;
  }
}

TEST(LineChartTest, MarkersLegendAndTranslucentBands) {
  ScratchDir dir("bands");
  LineChart chart;
  chart.title = "Data efficiency";
  chart.x_label = "demonstrations";
  chart.y_label = "success rate";
  for (int i = 0; i < 2; ++i) {
    LineChart::Series series;
    series.name = i == 0 ? "RECON" : "Baseline";
    series.x = {5, 10, 20, 40, 80};
    series.y = {0.3 + 0.1 * i, 0.45, 0.6 - 0.1 * i, 0.75, 0.85 - 0.1 * i};
    series.errors = {0.06, 0.05, 0.05, 0.04, 0.03};
    chart.series.push_back(series);
  }
  chart.references = {{0.9, "expert"}};
  const std::string path = dir.File("efficiency.png");
  WriteChart(chart, path);
  const PngImage image(path);
  EXPECT_GT(image.CountNear(PaletteColor(0), 2), 300u);
  EXPECT_GT(image.CountNear(PaletteColor(1), 2), 300u);
  // The band: the series colour at 20% over white, over a sizeable area.
  EXPECT_GT(image.CountNear(OverWhite(PaletteColor(0), 0.2), 3), 1000u);
}

TEST(LineChartTest, SvgIsText) {
  ScratchDir dir("line_svg");
  LineChart chart;
  chart.series = {Curve("a", 100, 1)};
  const std::string path = dir.File("line.svg");
  WriteChart(chart, path);
  const std::string svg = testing::ReadFile(path);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

}  // namespace
}  // namespace recon::report
