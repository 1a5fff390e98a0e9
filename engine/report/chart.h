#pragma once

#include <optional>
#include <string>
#include <vector>

namespace recon::report {

/// An sRGB colour, components in [0, 1].
struct Color {
  double r = 0, g = 0, b = 0;
};

/// Bars with standard-error whiskers, like the paper's result figures.
struct BarChart {
  std::string title;
  std::string subtitle;  ///< small text under the title (e.g. "15 runs per bar, seeds 1-15")
  std::string y_label;
  std::vector<std::string> labels;  ///< one per bar
  std::vector<double> values;
  std::vector<double> errors;  ///< half-length of each whisker (standard error); may be empty
  std::vector<Color> colors;   ///< one per bar; empty picks a palette
  /// Optional horizontal reference lines (e.g. "expert 17.79", "standing still 10.0").
  struct Reference {
    double value;
    std::string label;
  };
  std::vector<Reference> references;
  std::optional<double> y_min, y_max;  ///< axis range; unset fits the data
};

/// Lines with optional error bands (data-efficiency curves, loss curves).
struct LineChart {
  std::string title;
  std::string subtitle;
  std::string x_label;
  std::string y_label;
  bool log_y = false;
  struct Series {
    std::string name;
    std::vector<double> x, y;
    std::vector<double> errors;  ///< optional band half-width per point
    std::optional<Color> color;
    bool markers = true;
  };
  std::vector<Series> series;
  std::vector<BarChart::Reference> references;
};

/// Writes the chart to `path`; the format follows the extension (.png or .svg). Throws
/// UserError if the path cannot be written or the chart is malformed (sizes disagree).
void WriteChart(const BarChart& chart, const std::string& path, int width = 960, int height = 540);
void WriteChart(const LineChart& chart, const std::string& path, int width = 960, int height = 540);

/// The palette used when a chart names no colours (colour-blind safe).
Color PaletteColor(int index);

}  // namespace recon::report
