#include "engine/report/heat_map.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/core/color_scale.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/report/canvas.h"
#include "engine/report/chart_frame.h"
#include "engine/report/output.h"
#include "engine/report/ticks.h"

namespace recon::report {

namespace {

/// The project's sequential scale (engine/core/color_scale.h), t in [0, 1].
Color Sequential(double t) {
  const std::array<double, 3> c = SequentialColor(t);
  return {c[0], c[1], c[2]};
}

void Validate(const HeatMap& map) {
  if (map.nx < 1 || map.ny < 1 ||
      map.values.size() != static_cast<size_t>(map.nx) * static_cast<size_t>(map.ny)) {
    throw UserError("a heat map of " + std::to_string(map.nx) + " x " + std::to_string(map.ny) +
                    " cells needs as many values, got " + std::to_string(map.values.size()));
  }
  for (double v : {map.x_min, map.x_max, map.y_min, map.y_max, map.scale_max}) {
    CheckFinite(v, "heat map range");
  }
  if (!(map.x_min < map.x_max) || !(map.y_min < map.y_max)) {
    throw UserError("a heat map needs a non-empty range in x and y");
  }
}

}  // namespace

void WriteChart(const HeatMap& map, const std::string& path, int width, int height) {
  const ImageFormat format = FormatFromPath(path);
  CheckImageSize(width, height);
  Validate(map);
  double top = map.scale_max;
  if (top <= 0) {
    for (double v : map.values) {
      if (std::isfinite(v)) top = std::max(top, v);
    }
  }
  if (top <= 0) top = 1;  // all zero: one colour, and the bar still reads 0 to 1

  Canvas canvas(format, width, height);
  const Style style = Style::For(width, height);
  cairo_t* cr = canvas.cr();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  DrawTitleBlock(canvas, style, map.title, map.subtitle, width);
  const double title = TitleBlockHeight(canvas, style, map.title, map.subtitle, width);
  const AxisTicks x_ticks = LinearTicks(map.x_min, map.x_max, 5);
  const AxisTicks y_ticks = LinearTicks(map.y_min, map.y_max, 5);
  // Which table axis runs across the page and which up it.
  const double across = map.robot_view ? map.y_max - map.y_min : map.x_max - map.x_min;
  const double up = map.robot_view ? map.x_max - map.x_min : map.y_max - map.y_min;
  const double left =
      style.pad + 2.5 * canvas.LineHeight(style.axis_label) + canvas.TextWidth("-0.00", style.tick);
  const double bar_width = 16 * style.scale;
  const double right = style.pad + bar_width + 3 * style.gap +
                       canvas.TextWidth("0.000", style.tick) + canvas.LineHeight(style.axis_label);
  const double bottom = style.pad + 2.5 * canvas.LineHeight(style.tick);
  // The table drawn to scale: a metre is as long across as up.
  double plot_w = width - left - right, plot_h = height - title - bottom;
  if (plot_w / plot_h > across / up) {
    plot_w = plot_h * across / up;
  } else {
    plot_h = plot_w * up / across;
  }
  const Rect plot{left, title, plot_w, plot_h};
  // Table (x, y) to the page.
  const auto page_x = [&](double x, double y) {
    return map.robot_view ? plot.x + (map.y_max - y) / across * plot.w
                          : plot.x + (x - map.x_min) / across * plot.w;
  };
  const auto page_y = [&](double x, double y) {
    return map.robot_view ? plot.Bottom() - (x - map.x_min) / up * plot.h
                          : plot.Bottom() - (y - map.y_min) / up * plot.h;
  };
  const double cell_x = (map.x_max - map.x_min) / map.nx, cell_y = (map.y_max - map.y_min) / map.ny;
  for (int iy = 0; iy < map.ny; ++iy) {
    for (int ix = 0; ix < map.nx; ++ix) {
      const double v = map.values[static_cast<size_t>(iy) * map.nx + ix];
      const Color c = std::isfinite(v) ? Sequential(v / top) : Color{0.93, 0.93, 0.93};
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      const double x0 = map.x_min + ix * cell_x, y0 = map.y_min + iy * cell_y;
      const double ax = page_x(x0, y0), ay = page_y(x0, y0);
      const double bx = page_x(x0 + cell_x, y0 + cell_y), by = page_y(x0 + cell_x, y0 + cell_y);
      // Half a pixel wider so neighbouring cells leave no hairline between them.
      cairo_rectangle(cr, std::min(ax, bx), std::min(ay, by), std::abs(bx - ax) + 0.5,
                      std::abs(by - ay) + 0.5);
      cairo_fill(cr);
    }
  }
  cairo_set_source_rgb(cr, style.axis_line.r, style.axis_line.g, style.axis_line.b);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, Crisp(plot.x, 1), Crisp(plot.y, 1), plot.w, plot.h);
  cairo_stroke(cr);
  const AxisTicks& across_ticks = map.robot_view ? y_ticks : x_ticks;
  const AxisTicks& up_ticks = map.robot_view ? x_ticks : y_ticks;
  for (double t : across_ticks.values) {
    const double x = map.robot_view ? map.x_min : t, y = map.robot_view ? t : map.y_min;
    if (t < (map.robot_view ? map.y_min : map.x_min) - 1e-9 ||
        t > (map.robot_view ? map.y_max : map.x_max) + 1e-9) {
      continue;
    }
    canvas.Text(FormatTick(t, across_ticks.step), page_x(x, y), plot.Bottom() + style.gap,
                style.tick, style.ink, HAlign::kCenter, VAlign::kTop);
  }
  for (double t : up_ticks.values) {
    const double x = map.robot_view ? t : map.x_min, y = map.robot_view ? map.y_min : t;
    if (t < (map.robot_view ? map.x_min : map.y_min) - 1e-9 ||
        t > (map.robot_view ? map.x_max : map.y_max) + 1e-9) {
      continue;
    }
    canvas.Text(FormatTick(t, up_ticks.step), plot.x - style.gap, page_y(x, y), style.tick,
                style.ink, HAlign::kRight, VAlign::kMiddle);
  }
  canvas.Text(map.robot_view ? map.y_label : map.x_label, plot.x + plot.w / 2,
              plot.Bottom() + 2 * style.gap + canvas.LineHeight(style.tick), style.axis_label,
              style.ink, HAlign::kCenter, VAlign::kTop);
  canvas.Text(map.robot_view ? map.x_label : map.y_label, style.pad, plot.y + plot.h / 2,
              style.axis_label, style.ink, HAlign::kCenter, VAlign::kTop, -M_PI / 2);
  for (const HeatMap::Marker& m : map.markers) {
    const double mx = page_x(m.x, m.y), my = page_y(m.x, m.y);
    cairo_new_path(cr);  // the text above left a current point: start the circle afresh
    cairo_arc(cr, mx, my, 5 * style.scale, 0, 2 * M_PI);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.5 * style.scale);
    cairo_stroke(cr);
    canvas.Text(m.label, mx + 8 * style.scale, my, style.value, style.ink, HAlign::kLeft,
                VAlign::kMiddle, 0, true);
  }
  // The colour bar, 0 at the bottom.
  const double bar_x = plot.Right() + 2 * style.gap;
  constexpr int kSteps = 64;
  for (int i = 0; i < kSteps; ++i) {
    const Color c = Sequential((i + 0.5) / kSteps);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, bar_x, plot.Bottom() - (i + 1) * plot.h / kSteps, bar_width,
                    plot.h / kSteps + 0.5);
    cairo_fill(cr);
  }
  const AxisTicks bar_ticks = LinearTicks(0, top, 4);
  double widest = 0;
  for (double t : bar_ticks.values) {
    if (t > top + 1e-12) continue;
    const std::string label = FormatTick(t, bar_ticks.step);
    widest = std::max(widest, canvas.TextWidth(label, style.tick));
    canvas.Text(label, bar_x + bar_width + style.gap, plot.Bottom() - t / top * plot.h, style.tick,
                style.ink, HAlign::kLeft, VAlign::kMiddle);
  }
  canvas.Text(map.value_label, bar_x + bar_width + 2 * style.gap + widest, plot.y + plot.h / 2,
              style.axis_label, style.ink, HAlign::kCenter, VAlign::kTop, -M_PI / 2);
  recon::WriteFileAtomically(path, canvas.Encode());
}

}  // namespace recon::report
