// Drawing of BarChart; the geometry comes from bar_layout.cc.
#include <algorithm>
#include <cmath>

#include "engine/core/files.h"
#include "engine/report/bar_layout.h"
#include "engine/report/chart.h"
#include "engine/report/output.h"

namespace recon::report {
namespace {

const Color kWhisker{0, 0, 0};

void DrawBars(Canvas& canvas, const BarChart& chart, const BarLayout& layout) {
  cairo_t* cr = canvas.cr();
  const double base_y = layout.axis.ToPixel(layout.baseline, layout.plot);
  for (size_t i = 0; i < chart.values.size(); ++i) {
    const double top_y = layout.axis.ToPixel(chart.values[i], layout.plot);
    const double x = layout.center_x[i] - layout.bar_width / 2;
    cairo_rectangle(cr, x, std::min(top_y, base_y), layout.bar_width, std::abs(base_y - top_y));
    canvas.SetColor(chart.colors.empty() ? PaletteColor(static_cast<int>(i)) : chart.colors[i]);
    cairo_fill(cr);
  }
}

void DrawWhiskers(Canvas& canvas, const BarChart& chart, const BarLayout& layout) {
  if (chart.errors.empty()) return;
  cairo_t* cr = canvas.cr();
  const double s = layout.style.scale;
  const double cap = std::min(layout.bar_width * 0.35, 14 * s);
  cairo_set_line_width(cr, 1.5 * s);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  canvas.SetColor(kWhisker);
  for (size_t i = 0; i < chart.values.size(); ++i) {
    if (chart.errors[i] == 0) continue;
    const double x = layout.center_x[i];
    const double y_hi = layout.axis.ToPixel(chart.values[i] + chart.errors[i], layout.plot);
    const double y_lo = layout.axis.ToPixel(chart.values[i] - chart.errors[i], layout.plot);
    cairo_move_to(cr, x, y_lo);
    cairo_line_to(cr, x, y_hi);
    for (const double y : {y_lo, y_hi}) {
      cairo_move_to(cr, x - cap / 2, y);
      cairo_line_to(cr, x + cap / 2, y);
    }
  }
  cairo_stroke(cr);
}

void DrawValueLabels(Canvas& canvas, const BarChart& chart, const BarLayout& layout) {
  double largest = 0;
  for (const double value : chart.values) largest = std::max(largest, std::abs(value));
  const Style& style = layout.style;
  const double line = canvas.LineHeight(layout.value_font);
  for (size_t i = 0; i < chart.values.size(); ++i) {
    const double value = chart.values[i];
    const double error = chart.errors.empty() ? 0 : chart.errors[i];
    const std::string text = FormatValue(value, largest);
    if (value >= layout.baseline) {
      // Kept inside the plot even when a user y_max cuts the bar.
      const double y = std::max(layout.axis.ToPixel(value + error, layout.plot) - style.gap,
                                layout.plot.y + line);
      canvas.Text(text, layout.center_x[i], y, layout.value_font, style.ink, HAlign::kCenter,
                  VAlign::kBottom, 0, true);
    } else {
      const double y = std::min(layout.axis.ToPixel(value - error, layout.plot) + style.gap,
                                layout.plot.Bottom() - line);
      canvas.Text(text, layout.center_x[i], y, layout.value_font, style.ink, HAlign::kCenter,
                  VAlign::kTop, 0, true);
    }
  }
}

void DrawBarLabels(Canvas& canvas, const BarLayout& layout) {
  const Style& style = layout.style;
  const double y = layout.plot.Bottom() + style.gap;
  const double line = canvas.LineHeight(style.bar_label);
  for (size_t i = 0; i < layout.label_lines.size(); ++i) {
    const auto& lines = layout.label_lines[i];
    if (layout.label_angle_rad == 0) {
      for (size_t k = 0; k < lines.size(); ++k) {
        canvas.Text(lines[k], layout.center_x[i], y + k * line, style.bar_label, style.ink,
                    HAlign::kCenter, VAlign::kTop);
      }
    } else {
      // Text ends at the bar centre and runs down-left, so each label points at its bar.
      canvas.Text(lines[0], layout.center_x[i], y, style.bar_label, style.ink, HAlign::kRight,
                  VAlign::kMiddle, -layout.label_angle_rad);
    }
  }
}

}  // namespace

void WriteChart(const BarChart& chart, const std::string& path, int width, int height) {
  const ImageFormat format = FormatFromPath(path);
  CheckImageSize(width, height);
  ValidateBarChart(chart);

  Canvas canvas(format, width, height);
  const BarLayout layout = LayoutBarChart(canvas, chart, width, height);
  cairo_t* cr = canvas.cr();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  DrawTitleBlock(canvas, layout.style, chart.title, chart.subtitle, width);
  DrawGrid(canvas, layout.style, layout.plot, layout.axis);

  cairo_save(cr);
  // Bars and whiskers beyond a user-chosen y range are cut at the plot edge.
  cairo_rectangle(cr, layout.plot.x, layout.plot.y, layout.plot.w, layout.plot.h);
  cairo_clip(cr);
  DrawBars(canvas, chart, layout);
  DrawWhiskers(canvas, chart, layout);
  cairo_restore(cr);

  DrawReferences(canvas, layout.style, layout.plot, layout.axis, chart.references);
  DrawYAxis(canvas, layout.style, layout.plot, layout.axis, chart.y_label);
  DrawValueLabels(canvas, chart, layout);
  DrawBarLabels(canvas, layout);
  recon::WriteFileAtomically(path, canvas.Encode());
}

}  // namespace recon::report
