#pragma once

#include <string>
#include <vector>

#include "engine/report/canvas.h"
#include "engine/report/chart.h"
#include "engine/report/chart_frame.h"

namespace recon::report {

/// Where every part of a bar chart goes, in device pixels. Computed once and used both to draw
/// and by tests to know where a bar should be.
struct BarLayout {
  Style style;
  double width = 0, height = 0;
  Rect plot;
  ValueAxis axis;
  double baseline = 0;  ///< the value bars grow from: the axis end nearest to 0
  double bar_width = 0;
  std::vector<double> center_x;  ///< one per bar
  /// Under-bar labels: wrapped into lines when they fit the bar's slot, otherwise one rotated
  /// line each at `label_angle_rad` (0 when wrapped).
  std::vector<std::vector<std::string>> label_lines;
  double label_angle_rad = 0;
  Font value_font;  ///< shrunk from style.value when many bars leave little room
};

/// Throws UserError naming the offending field when the chart is malformed: sizes of
/// labels/errors/colors disagree with values, non-finite numbers, negative errors, no bars,
/// y_min >= y_max.
void ValidateBarChart(const BarChart& chart);

/// Lays out a valid chart, measuring text on `canvas`.
BarLayout LayoutBarChart(Canvas& canvas, const BarChart& chart, int width, int height);
/// Same, measuring on a scratch surface (for callers that only want the geometry).
BarLayout LayoutBarChart(const BarChart& chart, int width, int height);

}  // namespace recon::report
