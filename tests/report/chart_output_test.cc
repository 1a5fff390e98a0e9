// File handling and validation shared by both chart kinds: formats, errors, atomic writes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <set>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/report/chart.h"
#include "tests/report/test_support.h"

namespace recon::report {
namespace {

using ::testing::HasSubstr;
using testing::PaperBarChart;
using testing::ReadFile;
using testing::ScratchDir;

// Runs `write`, expects a UserError whose message contains `needle`, and returns the message.
std::string ExpectUserError(const std::function<void()>& write, const std::string& needle) {
  try {
    write();
  } catch (const UserError& error) {
    EXPECT_THAT(error.what(), HasSubstr(needle));
    return error.what();
  }
  ADD_FAILURE() << "no UserError mentioning '" << needle << "'";
  return "";
}

LineChart SimpleLineChart() {
  LineChart chart;
  LineChart::Series series;
  series.name = "s";
  series.x = {0, 1, 2, 3};
  series.y = {1, 2, 3, 4};
  chart.series.push_back(series);
  return chart;
}

TEST(ChartOutputTest, SvgOutputIsSvgText) {
  ScratchDir dir("svg");
  const std::string path = dir.File("bars.SVG");
  WriteChart(PaperBarChart(), path);
  const std::string svg = ReadFile(path);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("960"), std::string::npos);
  EXPECT_EQ(dir.Entries(), std::set<std::string>{"bars.SVG"});
}

TEST(ChartOutputTest, MalformedBarChartsNameTheField) {
  ScratchDir dir("bad_bars");
  const std::string path = dir.File("bars.png");
  auto expect = [&](const BarChart& chart, const std::string& field) {
    ExpectUserError([&] { WriteChart(chart, path); }, field);
  };
  BarChart chart = PaperBarChart();
  chart.labels.pop_back();
  expect(chart, "labels");
  chart = PaperBarChart();
  chart.errors.push_back(0.1);
  expect(chart, "errors");
  chart = PaperBarChart();
  chart.colors = {Color{0, 0, 0}};
  expect(chart, "colors");
  chart = PaperBarChart();
  chart.values[2] = std::nan("");
  expect(chart, "values[2]");
  chart = PaperBarChart();
  chart.errors[3] = -0.1;
  expect(chart, "errors[3]");
  chart = PaperBarChart();
  chart.references[0].value = INFINITY;
  expect(chart, "references[0]");
  chart = PaperBarChart();
  chart.y_min = 20;
  chart.y_max = 10;
  expect(chart, "y_min");
  expect(BarChart{}, "no bars");
  EXPECT_TRUE(dir.Entries().empty()) << "a rejected chart leaves no file behind";
}

TEST(ChartOutputTest, MalformedLineChartsNameTheField) {
  ScratchDir dir("bad_lines");
  const std::string path = dir.File("lines.png");
  auto expect = [&](const LineChart& chart, const std::string& field) {
    ExpectUserError([&] { WriteChart(chart, path); }, field);
  };
  LineChart chart = SimpleLineChart();
  chart.series[0].y.pop_back();
  expect(chart, "series[0] ('s').y");
  chart = SimpleLineChart();
  chart.series[0].y[3] = std::nan("");
  expect(chart, "y[3]");
  chart = SimpleLineChart();
  chart.series[0].x[1] = -INFINITY;
  expect(chart, "x[1]");
  chart = SimpleLineChart();
  chart.series[0].errors = {0.1};
  expect(chart, "errors");
  expect(LineChart{}, "no series");
  chart = LineChart{};
  chart.series.resize(2);
  expect(chart, "no data");
  EXPECT_TRUE(dir.Entries().empty());
}

TEST(ChartOutputTest, BadSizesAndExtensionsAreUserErrors) {
  ScratchDir dir("bad_args");
  ExpectUserError([&] { WriteChart(PaperBarChart(), dir.File("bars.jpg")); }, "bars.jpg");
  ExpectUserError([&] { WriteChart(PaperBarChart(), dir.File("bars")); }, ".png or .svg");
  ExpectUserError([&] { WriteChart(PaperBarChart(), dir.File("a.png"), 0, 540); }, "width");
  ExpectUserError([&] { WriteChart(SimpleLineChart(), dir.File("a.png"), 960, -1); }, "height");
  EXPECT_TRUE(dir.Entries().empty());
}

TEST(ChartOutputTest, UnwritablePathsNameThePath) {
  ScratchDir dir("unwritable");
  const std::string missing = "/nonexistent-recon-dir/sub/bars.png";
  ExpectUserError([&] { WriteChart(PaperBarChart(), missing); }, missing);
  EXPECT_FALSE(std::filesystem::exists(TemporarySibling(missing)));

  // A regular file used as a folder fails even for root, which ignores permission bits.
  { std::ofstream(dir.File("plain.txt")) << "not a folder"; }
  const std::string under_file = dir.File("plain.txt") + "/lines.svg";
  ExpectUserError([&] { WriteChart(SimpleLineChart(), under_file); }, under_file);

  // A folder where the chart should go: the rename fails and the temporary file is cleaned up.
  std::filesystem::create_directory(dir.File("taken.png"));
  ExpectUserError([&] { WriteChart(PaperBarChart(), dir.File("taken.png")); }, "taken.png");
  EXPECT_EQ(dir.Entries(), (std::set<std::string>{"plain.txt", "taken.png"}));
}

TEST(ChartOutputTest, FailedWriteKeepsTheExistingFile) {
  ScratchDir dir("keep");
  const std::string path = dir.File("bars.png");
  WriteChart(PaperBarChart(), path);
  const std::string good = ReadFile(path);
  ASSERT_FALSE(good.empty());

  // The temporary file cannot be created: a folder already has its name.
  std::filesystem::create_directory(TemporarySibling(path));
  BarChart other = PaperBarChart();
  other.values[0] = 12;
  ExpectUserError([&] { WriteChart(other, path); }, path);
  EXPECT_EQ(ReadFile(path), good);
  std::filesystem::remove(TemporarySibling(path));

  // A malformed chart is rejected before anything is written.
  other.labels.clear();
  ExpectUserError([&] { WriteChart(other, path); }, "labels");
  EXPECT_EQ(ReadFile(path), good);
  EXPECT_EQ(dir.Entries(), std::set<std::string>{"bars.png"});
}

TEST(ChartOutputTest, WritingAgainReplacesTheFile) {
  ScratchDir dir("replace");
  const std::string path = dir.File("bars.png");
  WriteChart(PaperBarChart(), path);
  const std::string first = ReadFile(path);
  BarChart other = PaperBarChart();
  other.title = "another title";
  WriteChart(other, path);
  EXPECT_NE(ReadFile(path), first);
  EXPECT_EQ(dir.Entries(), std::set<std::string>{"bars.png"});
}

TEST(ChartOutputTest, PaletteIsDistinctAndWraps) {
  std::set<std::tuple<double, double, double>> colors;
  for (int i = 0; i < 8; ++i) {
    const Color c = PaletteColor(i);
    colors.insert({c.r, c.g, c.b});
    EXPECT_GE(c.r, 0);
    EXPECT_LE(c.b, 1);
  }
  EXPECT_EQ(colors.size(), 8u);
  // Okabe-Ito blue first.
  EXPECT_NEAR(PaletteColor(0).b, 0.698, 1e-3);
  // The ninth colour repeats the first hue but darker, so bars 1 and 9 differ.
  EXPECT_LT(PaletteColor(8).b, PaletteColor(0).b);
  EXPECT_NEAR(PaletteColor(8).b / PaletteColor(8).g, PaletteColor(0).b / PaletteColor(0).g, 1e-9);
  // The sequence wraps, negative indices included.
  EXPECT_DOUBLE_EQ(PaletteColor(24).b, PaletteColor(0).b);
  EXPECT_DOUBLE_EQ(PaletteColor(-1).g, PaletteColor(23).g);
}

}  // namespace
}  // namespace recon::report
