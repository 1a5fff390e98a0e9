// LineChart: validation, layout and drawing (the x axis is always linear, y linear or log10).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/report/chart.h"
#include "engine/report/chart_frame.h"
#include "engine/report/output.h"

namespace recon::report {
namespace {

using Series = LineChart::Series;

std::string SeriesField(size_t i, const Series& series, const std::string& field) {
  std::string name = "LineChart.series[" + std::to_string(i) + "]";
  if (!series.name.empty()) name += " ('" + series.name + "')";
  return name + "." + field;
}

void Validate(const LineChart& chart) {
  if (chart.series.empty()) throw UserError("LineChart has no series: LineChart.series is empty");
  size_t points = 0;
  for (size_t i = 0; i < chart.series.size(); ++i) {
    const Series& s = chart.series[i];
    if (s.y.size() != s.x.size()) {
      throw UserError(SeriesField(i, s, "y") + " has " + std::to_string(s.y.size()) +
                      " entries but x has " + std::to_string(s.x.size()));
    }
    if (!s.errors.empty() && s.errors.size() != s.x.size()) {
      throw UserError(SeriesField(i, s, "errors") + " has " + std::to_string(s.errors.size()) +
                      " entries but x has " + std::to_string(s.x.size()));
    }
    for (size_t k = 0; k < s.x.size(); ++k) {
      const std::string at = "[" + std::to_string(k) + "]";
      CheckFinite(s.x[k], SeriesField(i, s, "x" + at));
      CheckFinite(s.y[k], SeriesField(i, s, "y" + at));
      if (!s.errors.empty()) {
        CheckFinite(s.errors[k], SeriesField(i, s, "errors" + at));
        if (s.errors[k] < 0) throw UserError(SeriesField(i, s, "errors" + at) + " is negative");
      }
    }
    if (s.color) {
      for (const double c : {s.color->r, s.color->g, s.color->b}) {
        if (!(c >= 0 && c <= 1)) {
          throw UserError(SeriesField(i, s, "color") + " has a component outside [0, 1]");
        }
      }
    }
    points += s.x.size();
  }
  if (points == 0) throw UserError("LineChart has no data: every LineChart.series is empty");
  for (size_t i = 0; i < chart.references.size(); ++i) {
    CheckFinite(chart.references[i].value, "LineChart.references[" + std::to_string(i) + "].value");
  }
}

double ErrorAt(const Series& s, size_t k) { return s.errors.empty() ? 0 : s.errors[k]; }

ValueAxis FitYAxis(const LineChart& chart) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo = kInf, hi = -kInf;
  auto include = [&](double v) {
    // A log axis cannot show zero or below; such values are left out of the range.
    if (chart.log_y && !(v > 0)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  for (const Series& s : chart.series) {
    for (size_t k = 0; k < s.y.size(); ++k) {
      const double e = ErrorAt(s, k);
      include(s.y[k]);
      include(s.y[k] + e);
      include(s.y[k] - e);
    }
  }
  for (const auto& reference : chart.references) include(reference.value);
  ValueAxis axis;
  axis.log = chart.log_y;
  if (chart.log_y) {
    axis.ticks = lo <= hi ? LogTicks(lo, hi) : LogTicks(1, 10);
    return axis;
  }
  const double pad = 0.03 * (hi - lo);
  axis.ticks = LinearTicks(lo - pad, hi + pad, 6);
  return axis;
}

struct LegendEntry {
  size_t series;
  double width;
};

struct Layout {
  Style style;
  Rect plot;
  ValueAxis y_axis;
  AxisTicks x_ticks;
  double legend_top = 0;
  std::vector<std::vector<LegendEntry>> legend_rows;
  std::vector<bool> markers;  ///< per series, after density thinning
};

double XToPixel(const Layout& layout, double x) {
  const double span = layout.x_ticks.hi - layout.x_ticks.lo;
  return layout.plot.x + (x - layout.x_ticks.lo) / span * layout.plot.w;
}

Layout LayOut(Canvas& canvas, const LineChart& chart, int width, int height) {
  Layout layout;
  layout.style = Style::For(width, height);
  const Style& style = layout.style;
  const double swatch = 22 * style.scale;
  const double legend_line = canvas.LineHeight(style.legend);

  layout.legend_top = TitleBlockHeight(canvas, style, chart.title, chart.subtitle, width);
  double row_width = 0;
  for (size_t i = 0; i < chart.series.size(); ++i) {
    if (chart.series[i].name.empty()) continue;
    const double w = swatch + style.gap + canvas.TextWidth(chart.series[i].name, style.legend);
    const double spacing = 3 * style.gap;
    if (layout.legend_rows.empty() || row_width + spacing + w > width - 2 * style.pad) {
      layout.legend_rows.emplace_back();
      row_width = 0;
    } else {
      row_width += spacing;
    }
    layout.legend_rows.back().push_back({i, w});
    row_width += w;
  }
  const double top = layout.legend_top + layout.legend_rows.size() * (legend_line + style.gap) +
                     (layout.legend_rows.empty() ? 0 : style.gap);

  layout.y_axis = FitYAxis(chart);
  const double left = YAxisMargin(canvas, style, layout.y_axis, chart.y_label);
  const double tick_line = canvas.LineHeight(style.tick);
  const double x_label = chart.x_label.empty() ? 0 : canvas.LineHeight(style.axis_label);
  const double bottom = style.pad + x_label + style.gap + tick_line + style.tick_length + style.gap;

  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (const Series& s : chart.series) {
    for (const double x : s.x) {
      x_lo = std::min(x_lo, x);
      x_hi = std::max(x_hi, x);
    }
  }
  // Fewer x ticks until their labels leave clear space between them.
  const double reference_margin = ReferenceMargin(canvas, style, chart.references);
  double right = style.pad + reference_margin;
  double plot_w = width - left - right;
  for (int target = std::clamp(static_cast<int>(plot_w / (90 * style.scale)), 2, 10);; --target) {
    layout.x_ticks = LinearTicks(x_lo, x_hi, target);
    double widest = 0;
    for (const double x : layout.x_ticks.values) {
      widest = std::max(widest, canvas.TextWidth(FormatTick(x, layout.x_ticks.step), style.tick));
    }
    if (reference_margin == 0) right = style.pad + widest / 2;
    plot_w = width - left - right;
    const double spacing = plot_w / std::max<size_t>(1, layout.x_ticks.values.size() - 1);
    if (widest + 2 * style.gap <= spacing || target <= 1) break;
  }
  layout.plot = {left, top, plot_w, height - top - bottom};
  for (const Series& s : chart.series) {
    // Markers on a dense curve merge into a thick smear; past one per 6 px they are dropped.
    layout.markers.push_back(s.markers && s.x.size() * 6 * style.scale <= layout.plot.w);
  }
  return layout;
}

void DrawXAxis(Canvas& canvas, const LineChart& chart, const Layout& layout) {
  const Style& style = layout.style;
  const Rect& plot = layout.plot;
  cairo_t* cr = canvas.cr();
  const double line = std::max(1.0, std::round(style.scale));
  cairo_set_line_width(cr, line);
  canvas.SetColor(style.axis_line);
  for (const double x : layout.x_ticks.values) {
    const double px = Crisp(XToPixel(layout, x), line);
    cairo_move_to(cr, px, plot.Bottom());
    cairo_line_to(cr, px, plot.Bottom() + style.tick_length);
  }
  cairo_stroke(cr);
  const double label_y = plot.Bottom() + style.tick_length + style.gap / 2;
  for (const double x : layout.x_ticks.values) {
    canvas.Text(FormatTick(x, layout.x_ticks.step), XToPixel(layout, x), label_y, style.tick,
                style.ink, HAlign::kCenter, VAlign::kTop);
  }
  if (!chart.x_label.empty()) {
    canvas.Text(Ellipsize(canvas, chart.x_label, style.axis_label, plot.w), plot.x + plot.w / 2,
                label_y + canvas.LineHeight(style.tick) + style.gap, style.axis_label, style.ink,
                HAlign::kCenter, VAlign::kTop);
  }
}

void DrawVerticalGrid(Canvas& canvas, const Layout& layout) {
  cairo_t* cr = canvas.cr();
  const double line = std::max(1.0, std::round(layout.style.scale));
  cairo_set_line_width(cr, line);
  canvas.SetColor(layout.style.grid);
  for (const double x : layout.x_ticks.values) {
    const double px = Crisp(XToPixel(layout, x), line);
    cairo_move_to(cr, px, layout.plot.y);
    cairo_line_to(cr, px, layout.plot.Bottom());
  }
  cairo_stroke(cr);
}

// Runs of consecutive points the axis can show (all of them unless log_y meets y <= 0).
std::vector<std::pair<size_t, size_t>> Runs(const Series& s, bool log_y) {
  std::vector<std::pair<size_t, size_t>> runs;
  size_t k = 0;
  while (k < s.y.size()) {
    while (k < s.y.size() && log_y && !(s.y[k] > 0)) ++k;
    const size_t begin = k;
    while (k < s.y.size() && (!log_y || s.y[k] > 0)) ++k;
    if (k > begin) runs.push_back({begin, k});
  }
  return runs;
}

void DrawSeries(Canvas& canvas, const Series& s, const Color& color, bool markers,
                const Layout& layout, bool log_y) {
  cairo_t* cr = canvas.cr();
  const Style& style = layout.style;
  auto px = [&](size_t k) { return XToPixel(layout, s.x[k]); };
  auto py = [&](double v) { return layout.y_axis.ToPixel(v, layout.plot); };
  const auto runs = Runs(s, log_y);
  if (!s.errors.empty()) {
    for (const auto& [begin, end] : runs) {
      cairo_move_to(cr, px(begin), py(s.y[begin] + s.errors[begin]));
      for (size_t k = begin + 1; k < end; ++k) cairo_line_to(cr, px(k), py(s.y[k] + s.errors[k]));
      // On a log axis a lower edge at or below zero maps to the bottom of the plot.
      for (size_t k = end; k-- > begin;) cairo_line_to(cr, px(k), py(s.y[k] - s.errors[k]));
      cairo_close_path(cr);
    }
    canvas.SetColor(color, 0.2);
    cairo_fill(cr);
  }
  for (const auto& [begin, end] : runs) {
    cairo_move_to(cr, px(begin), py(s.y[begin]));
    for (size_t k = begin + 1; k < end; ++k) cairo_line_to(cr, px(k), py(s.y[k]));
  }
  // A curve with more points than pixel columns is mostly noise wiggle; a thin line keeps the
  // trend readable and overlapping curves distinguishable.
  const bool dense = static_cast<double>(s.x.size()) > layout.plot.w / style.scale;
  cairo_set_line_width(cr, (dense ? 1.3 : 2.0) * style.scale);
  canvas.SetColor(color);
  cairo_stroke(cr);
  if (!markers) return;
  const double radius = 3.5 * style.scale;
  for (const auto& [begin, end] : runs) {
    for (size_t k = begin; k < end; ++k) {
      cairo_new_sub_path(cr);
      cairo_arc(cr, px(k), py(s.y[k]), radius, 0, 2 * std::numbers::pi);
    }
  }
  canvas.SetColor(color);
  cairo_fill_preserve(cr);
  cairo_set_line_width(cr, 1 * style.scale);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_stroke(cr);
}

Color SeriesColor(const LineChart& chart, size_t i) {
  return chart.series[i].color.value_or(PaletteColor(static_cast<int>(i)));
}

void DrawLegend(Canvas& canvas, const LineChart& chart, const Layout& layout, double width) {
  const Style& style = layout.style;
  cairo_t* cr = canvas.cr();
  const double swatch = 22 * style.scale;
  const double spacing = 3 * style.gap;
  const double line = canvas.LineHeight(style.legend);
  double y = layout.legend_top;
  for (const auto& row : layout.legend_rows) {
    double row_width = -spacing;
    for (const LegendEntry& entry : row) row_width += entry.width + spacing;
    double x = (width - row_width) / 2;
    const double mid = y + line / 2;
    for (const LegendEntry& entry : row) {
      const Series& s = chart.series[entry.series];
      const Color color = SeriesColor(chart, entry.series);
      if (!s.errors.empty()) {
        cairo_rectangle(cr, x, mid - line * 0.35, swatch, line * 0.7);
        canvas.SetColor(color, 0.2);
        cairo_fill(cr);
      }
      cairo_move_to(cr, x, mid);
      cairo_line_to(cr, x + swatch, mid);
      cairo_set_line_width(cr, 2 * style.scale);
      canvas.SetColor(color);
      cairo_stroke(cr);
      if (layout.markers[entry.series]) {
        cairo_arc(cr, x + swatch / 2, mid, 3.5 * style.scale, 0, 2 * std::numbers::pi);
        cairo_fill(cr);
      }
      canvas.Text(s.name, x + swatch + style.gap, mid, style.legend, style.ink, HAlign::kLeft,
                  VAlign::kMiddle);
      x += entry.width + spacing;
    }
    y += line + style.gap;
  }
}

}  // namespace

void WriteChart(const LineChart& chart, const std::string& path, int width, int height) {
  const ImageFormat format = FormatFromPath(path);
  CheckImageSize(width, height);
  Validate(chart);

  Canvas canvas(format, width, height);
  const Layout layout = LayOut(canvas, chart, width, height);
  cairo_t* cr = canvas.cr();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  DrawTitleBlock(canvas, layout.style, chart.title, chart.subtitle, width);
  DrawLegend(canvas, chart, layout, width);
  DrawVerticalGrid(canvas, layout);
  DrawGrid(canvas, layout.style, layout.plot, layout.y_axis);
  DrawReferences(canvas, layout.style, layout.plot, layout.y_axis, chart.references);

  cairo_save(cr);
  // The margin lets markers on the axis ends show whole.
  const double margin = 5 * layout.style.scale;
  cairo_rectangle(cr, layout.plot.x - margin, layout.plot.y - margin, layout.plot.w + 2 * margin,
                  layout.plot.h + 2 * margin);
  cairo_clip(cr);
  for (size_t i = 0; i < chart.series.size(); ++i) {
    DrawSeries(canvas, chart.series[i], SeriesColor(chart, i), layout.markers[i], layout,
               chart.log_y);
  }
  cairo_restore(cr);

  DrawYAxis(canvas, layout.style, layout.plot, layout.y_axis, chart.y_label);
  DrawXAxis(canvas, chart, layout);
  recon::WriteFileAtomically(path, canvas.Encode());
}

}  // namespace recon::report
