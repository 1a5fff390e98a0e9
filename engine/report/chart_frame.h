#pragma once

#include <string>
#include <vector>

#include "engine/report/canvas.h"
#include "engine/report/chart.h"
#include "engine/report/ticks.h"

namespace recon::report {

/// An axis-aligned rectangle in device pixels.
struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
  double Right() const { return x + w; }
  double Bottom() const { return y + h; }
};

/// Fonts, spacing and ink shared by every chart. Sizes are in device pixels for a 960 x 540
/// image and grow with the image, so a 1920 x 1080 render looks like a 2x-DPI 960 x 540 one.
struct Style {
  double scale = 1;
  Font title, subtitle, axis_label, tick, bar_label, value, legend, reference;
  double pad = 14, gap = 6, tick_length = 5;
  Color ink{0.12, 0.12, 0.12};
  Color muted{0.35, 0.35, 0.35};
  Color grid{0.88, 0.88, 0.88};
  Color minor_grid{0.95, 0.95, 0.95};
  Color axis_line{0.25, 0.25, 0.25};
  Color reference_ink{0.3, 0.3, 0.3};

  static Style For(int width, int height);
};

/// The vertical value axis: ticks plus the mapping from data to pixels (linear or log10).
struct ValueAxis {
  AxisTicks ticks;
  bool log = false;
  /// Pixel row of `value` in `plot`; on a log axis non-positive values map to the bottom.
  double ToPixel(double value, const Rect& plot) const;
  std::string Label(double value) const;
};

/// Throws UserError naming width/height when the image size is unusable.
void CheckImageSize(int width, int height);
/// Throws UserError naming `field` when `value` is NaN or infinite.
void CheckFinite(double value, const std::string& field);

/// `text`, shortened with an ellipsis until it fits in `max_width` pixels.
std::string Ellipsize(Canvas& canvas, const std::string& text, const Font& font, double max_width);

/// Height taken by the title and subtitle, including the space under them.
double TitleBlockHeight(Canvas& canvas, const Style& style, const std::string& title,
                        const std::string& subtitle, double width);
void DrawTitleBlock(Canvas& canvas, const Style& style, const std::string& title,
                    const std::string& subtitle, double width);

/// Width needed left of the plot for the y label and tick labels.
double YAxisMargin(Canvas& canvas, const Style& style, const ValueAxis& axis,
                   const std::string& label);
void DrawGrid(Canvas& canvas, const Style& style, const Rect& plot, const ValueAxis& axis);
/// Left and bottom spines, y ticks with labels, and the rotated y label.
void DrawYAxis(Canvas& canvas, const Style& style, const Rect& plot, const ValueAxis& axis,
               const std::string& label);

/// Width needed right of the plot for reference labels (0 when there are none).
double ReferenceMargin(Canvas& canvas, const Style& style,
                       const std::vector<BarChart::Reference>& references);
/// Dashed lines across the plot, labelled in the right margin; labels of close references are
/// pushed apart so they never overlap. References outside the axis range are left out.
void DrawReferences(Canvas& canvas, const Style& style, const Rect& plot, const ValueAxis& axis,
                    const std::vector<BarChart::Reference>& references);

}  // namespace recon::report
