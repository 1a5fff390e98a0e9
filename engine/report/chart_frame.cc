#include "engine/report/chart_frame.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/core/error.h"

namespace recon::report {
namespace {

// Past this, a cairo image surface needs gigabytes; nobody means it.
constexpr int kMaxImageSide = 16384;
constexpr double kMinTitleSize = 10;

std::string ReferenceText(const BarChart::Reference& reference) {
  if (!reference.label.empty()) return reference.label;
  return FormatValue(reference.value, reference.value);
}

// The title shrinks before it is cut: a long title in smaller type reads better than "...".
Font FittedFont(Canvas& canvas, const Style& style, const Font& font, const std::string& text,
                double width) {
  Font fitted = font;
  const double available = width - 2 * style.pad;
  const double natural = canvas.TextWidth(text, font);
  if (natural > available && natural > 0) {
    fitted.size = std::max(kMinTitleSize * style.scale, font.size * available / natural);
  }
  return fitted;
}

}  // namespace

Style Style::For(int width, int height) {
  Style style;
  const double s = std::clamp(std::min(width / 960.0, height / 540.0), 0.7, 4.0);
  style.scale = s;
  style.title = {19 * s, true, false};
  style.subtitle = {13 * s, false, false};
  style.axis_label = {14 * s, false, false};
  style.tick = {12 * s, false, false};
  style.bar_label = {12.5 * s, false, false};
  style.value = {12 * s, false, false};
  style.legend = {13 * s, false, false};
  style.reference = {12 * s, false, true};
  style.pad = 14 * s;
  style.gap = 6 * s;
  style.tick_length = 5 * s;
  return style;
}

double ValueAxis::ToPixel(double value, const Rect& plot) const {
  double t = 0;
  if (log) {
    const double lo = std::log10(ticks.lo);
    t = value > 0 ? (std::log10(value) - lo) / (std::log10(ticks.hi) - lo) : 0;
  } else {
    t = (value - ticks.lo) / (ticks.hi - ticks.lo);
  }
  return plot.Bottom() - t * plot.h;
}

std::string ValueAxis::Label(double value) const {
  return log ? FormatLogTick(value, UsePlainLogLabels(ticks)) : FormatTick(value, ticks.step);
}

void CheckImageSize(int width, int height) {
  if (width < 16 || width > kMaxImageSide) {
    throw UserError("chart width must be 16..16384 pixels, got " + std::to_string(width));
  }
  if (height < 16 || height > kMaxImageSide) {
    throw UserError("chart height must be 16..16384 pixels, got " + std::to_string(height));
  }
}

void CheckFinite(double value, const std::string& field) {
  if (!std::isfinite(value)) {
    throw UserError("chart field " + field + " is not a finite number (" + std::to_string(value) +
                    ")");
  }
}

std::string Ellipsize(Canvas& canvas, const std::string& text, const Font& font, double max_width) {
  if (canvas.TextWidth(text, font) <= max_width) return text;
  std::string cut = text;
  while (!cut.empty()) {
    cut.pop_back();
    // Never leave half of a UTF-8 sequence behind.
    while (!cut.empty() && (static_cast<unsigned char>(cut.back()) & 0xC0) == 0x80) cut.pop_back();
    if (!cut.empty() && (static_cast<unsigned char>(cut.back()) & 0xC0) == 0xC0) cut.pop_back();
    if (canvas.TextWidth(cut + "\u2026", font) <= max_width) return cut + "\u2026";
  }
  return "";
}

double TitleBlockHeight(Canvas& canvas, const Style& style, const std::string& title,
                        const std::string& subtitle, double width) {
  double height = style.pad;
  if (!title.empty()) {
    height += canvas.LineHeight(FittedFont(canvas, style, style.title, title, width));
  }
  if (!subtitle.empty()) {
    height += style.gap / 2 + canvas.LineHeight(style.subtitle);
  }
  return height + (title.empty() && subtitle.empty() ? 0 : 1.5 * style.gap);
}

void DrawTitleBlock(Canvas& canvas, const Style& style, const std::string& title,
                    const std::string& subtitle, double width) {
  double y = style.pad;
  const double available = width - 2 * style.pad;
  if (!title.empty()) {
    const Font font = FittedFont(canvas, style, style.title, title, width);
    canvas.Text(Ellipsize(canvas, title, font, available), width / 2, y, font, style.ink,
                HAlign::kCenter, VAlign::kTop);
    y += canvas.LineHeight(font);
  }
  if (!subtitle.empty()) {
    y += style.gap / 2;
    canvas.Text(Ellipsize(canvas, subtitle, style.subtitle, available), width / 2, y,
                style.subtitle, style.muted, HAlign::kCenter, VAlign::kTop);
  }
}

double YAxisMargin(Canvas& canvas, const Style& style, const ValueAxis& axis,
                   const std::string& label) {
  double widest = 0;
  for (const double value : axis.ticks.values) {
    widest = std::max(widest, canvas.TextWidth(axis.Label(value), style.tick));
  }
  const double label_width = label.empty() ? 0 : canvas.LineHeight(style.axis_label) + style.gap;
  return style.pad + label_width + widest + style.gap + style.tick_length;
}

void DrawGrid(Canvas& canvas, const Style& style, const Rect& plot, const ValueAxis& axis) {
  cairo_t* cr = canvas.cr();
  const double line = std::max(1.0, std::round(style.scale));
  cairo_set_line_width(cr, line);
  if (axis.log && axis.ticks.step == 10 && axis.ticks.values.size() <= 9) {
    // Minor lines at 2..9 x each decade make a log axis readable as one.
    canvas.SetColor(style.minor_grid);
    for (double decade = axis.ticks.lo; decade < axis.ticks.hi * 0.999; decade *= 10) {
      for (int k = 2; k <= 9; ++k) {
        const double y = Crisp(axis.ToPixel(k * decade, plot), line);
        cairo_move_to(cr, plot.x, y);
        cairo_line_to(cr, plot.Right(), y);
      }
    }
    cairo_stroke(cr);
  }
  canvas.SetColor(style.grid);
  for (const double value : axis.ticks.values) {
    const double y = Crisp(axis.ToPixel(value, plot), line);
    cairo_move_to(cr, plot.x, y);
    cairo_line_to(cr, plot.Right(), y);
  }
  cairo_stroke(cr);
}

void DrawYAxis(Canvas& canvas, const Style& style, const Rect& plot, const ValueAxis& axis,
               const std::string& label) {
  cairo_t* cr = canvas.cr();
  const double line = std::max(1.0, std::round(style.scale));
  cairo_set_line_width(cr, line);
  canvas.SetColor(style.axis_line);
  const double left = Crisp(plot.x, line);
  const double bottom = Crisp(plot.Bottom(), line);
  cairo_move_to(cr, left, plot.y);
  cairo_line_to(cr, left, bottom);
  cairo_line_to(cr, plot.Right(), bottom);
  for (const double value : axis.ticks.values) {
    const double y = Crisp(axis.ToPixel(value, plot), line);
    cairo_move_to(cr, left - style.tick_length, y);
    cairo_line_to(cr, left, y);
  }
  cairo_stroke(cr);
  double widest = 0;
  for (const double value : axis.ticks.values) {
    const std::string text = axis.Label(value);
    widest = std::max(widest, canvas.TextWidth(text, style.tick));
    canvas.Text(text, plot.x - style.tick_length - style.gap, axis.ToPixel(value, plot), style.tick,
                style.ink, HAlign::kRight, VAlign::kMiddle);
  }
  if (!label.empty()) {
    // Next to the tick labels rather than at the image edge: the left margin may have grown
    // for rotated bar labels, and a far-away axis title reads as belonging to nothing.
    const double x =
        plot.x - style.tick_length - 2 * style.gap - widest - canvas.LineHeight(style.axis_label);
    canvas.Text(Ellipsize(canvas, label, style.axis_label, plot.h), std::max(style.pad, x),
                plot.y + plot.h / 2, style.axis_label, style.ink, HAlign::kCenter, VAlign::kTop,
                -std::numbers::pi / 2);
  }
}

double ReferenceMargin(Canvas& canvas, const Style& style,
                       const std::vector<BarChart::Reference>& references) {
  double widest = 0;
  for (const auto& reference : references) {
    widest = std::max(widest, canvas.TextWidth(ReferenceText(reference), style.reference));
  }
  return references.empty() ? 0 : widest + 2 * style.gap;
}

void DrawReferences(Canvas& canvas, const Style& style, const Rect& plot, const ValueAxis& axis,
                    const std::vector<BarChart::Reference>& references) {
  struct Placed {
    double line_y;
    double label_y;
    std::string text;
  };
  std::vector<Placed> placed;
  for (const auto& reference : references) {
    const bool outside = axis.log
                             ? !(reference.value >= axis.ticks.lo * (1 - 1e-9) &&
                                 reference.value <= axis.ticks.hi * (1 + 1e-9))
                             : reference.value < axis.ticks.lo || reference.value > axis.ticks.hi;
    if (outside) continue;
    const double y = axis.ToPixel(reference.value, plot);
    placed.push_back({y, y, ReferenceText(reference)});
  }
  if (placed.empty()) return;

  cairo_t* cr = canvas.cr();
  cairo_save(cr);
  const double dashes[] = {6 * style.scale, 4 * style.scale};
  cairo_set_dash(cr, dashes, 2, 0);
  cairo_set_line_width(cr, 1.4 * style.scale);
  canvas.SetColor(style.reference_ink);
  for (const Placed& p : placed) {
    cairo_move_to(cr, plot.x, p.line_y);
    cairo_line_to(cr, plot.Right(), p.line_y);
  }
  cairo_stroke(cr);
  cairo_restore(cr);

  // Push labels apart top to bottom, then back up if the last one fell off the plot.
  std::sort(placed.begin(), placed.end(),
            [](const Placed& a, const Placed& b) { return a.line_y < b.line_y; });
  const double spacing = canvas.LineHeight(style.reference);
  for (size_t i = 1; i < placed.size(); ++i) {
    placed[i].label_y = std::max(placed[i].label_y, placed[i - 1].label_y + spacing);
  }
  const double limit = plot.Bottom() + spacing / 2;
  for (size_t i = placed.size(); i-- > 0;) {
    const double max_y = i + 1 < placed.size() ? placed[i + 1].label_y - spacing : limit;
    placed[i].label_y = std::min(placed[i].label_y, max_y);
  }
  for (const Placed& p : placed) {
    canvas.Text(p.text, plot.Right() + style.gap, p.label_y, style.reference, style.reference_ink,
                HAlign::kLeft, VAlign::kMiddle);
  }
}

}  // namespace recon::report
