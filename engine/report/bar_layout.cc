#include "engine/report/bar_layout.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "engine/core/error.h"

namespace recon::report {
namespace {

constexpr int kMaxWrappedLines = 3;
constexpr double kBarFraction = 0.68;      // of each bar's slot; the rest separates bars
constexpr double kMaxLabelFraction = 0.3;  // of the image height, for rotated labels

void CheckSize(size_t size, size_t bars, const char* field) {
  if (size != bars) {
    throw UserError(std::string("BarChart.") + field + " has " + std::to_string(size) +
                    " entries but values has " + std::to_string(bars));
  }
}

std::string Indexed(const char* field, size_t i) {
  return std::string("BarChart.") + field + "[" + std::to_string(i) + "]";
}

double Error(const BarChart& chart, size_t i) { return chart.errors.empty() ? 0 : chart.errors[i]; }

// Greedy word wrap; nullopt when a word alone is too wide or more than kMaxWrappedLines result.
std::optional<std::vector<std::string>> Wrap(Canvas& canvas, const std::string& text,
                                             const Font& font, double max_width) {
  std::vector<std::string> lines;
  std::string line;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    start = end + 1;
    if (word.empty()) continue;
    if (canvas.TextWidth(word, font) > max_width) return std::nullopt;
    const std::string joined = line.empty() ? word : line + " " + word;
    if (canvas.TextWidth(joined, font) <= max_width) {
      line = joined;
    } else {
      lines.push_back(line);
      line = word;
    }
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  if (lines.size() > kMaxWrappedLines) return std::nullopt;
  return lines;
}

// A nice axis below the smallest whisker end and above the largest, so differences between
// bars are visible (the paper's style), and never crossing 0 for one-signed data.
ValueAxis FitAxis(const BarChart& chart) {
  double lo = chart.values[0], hi = chart.values[0];
  for (size_t i = 0; i < chart.values.size(); ++i) {
    lo = std::min(lo, chart.values[i] - Error(chart, i));
    hi = std::max(hi, chart.values[i] + Error(chart, i));
  }
  for (const auto& reference : chart.references) {
    lo = std::min(lo, reference.value);
    hi = std::max(hi, reference.value);
  }
  const double pad = 0.05 * (hi - lo);
  double axis_lo = chart.y_min.value_or(lo - pad);
  double axis_hi = chart.y_max.value_or(hi + pad);
  if (!chart.y_min && lo >= 0 && axis_lo < 0) axis_lo = 0;
  if (!chart.y_max && hi <= 0 && axis_hi > 0) axis_hi = 0;
  // A lone bound given by the user on the wrong side of the data still needs a usable range.
  if (axis_hi <= axis_lo) {
    const double span = std::max(1.0, std::abs(axis_lo) * 0.1);
    if (chart.y_min)
      axis_hi = axis_lo + span;
    else
      axis_lo = axis_hi - span;
  }
  ValueAxis axis;
  axis.ticks = LinearTicks(axis_lo, axis_hi, 6);
  // User bounds are exact; ticks outside them go.
  if (chart.y_min) axis.ticks.lo = *chart.y_min;
  if (chart.y_max) axis.ticks.hi = *chart.y_max;
  std::erase_if(axis.ticks.values, [&](double v) {
    const double eps = 1e-9 * axis.ticks.step;
    return v < axis.ticks.lo - eps || v > axis.ticks.hi + eps;
  });
  return axis;
}

// Under-bar labels: wrapped if every label fits its slot, else all rotated (mixed looks messy).
void LayoutLabels(Canvas& canvas, const BarChart& chart, double slot, BarLayout& layout) {
  const Style& style = layout.style;
  layout.label_lines.clear();
  layout.label_angle_rad = 0;
  for (const std::string& label : chart.labels) {
    auto lines = Wrap(canvas, label, style.bar_label, slot * 0.92);
    if (!lines) break;
    layout.label_lines.push_back(*lines);
  }
  if (layout.label_lines.size() == chart.labels.size()) return;

  // Adjacent rotated labels sit slot * sin(angle) apart; keep that above a line and a bit.
  const double line = canvas.LineHeight(style.bar_label);
  const double angle = std::clamp(std::asin(std::min(1.0, 1.3 * line / slot)), std::numbers::pi / 6,
                                  std::numbers::pi / 2);
  const double max_width =
      (kMaxLabelFraction * layout.height - line * std::cos(angle)) / std::sin(angle);
  layout.label_lines.clear();
  for (const std::string& label : chart.labels) {
    layout.label_lines.push_back({Ellipsize(canvas, label, style.bar_label, max_width)});
  }
  layout.label_angle_rad = angle;
}

double LabelBlockHeight(Canvas& canvas, const BarLayout& layout) {
  const double line = canvas.LineHeight(layout.style.bar_label);
  double height = 0;
  for (const auto& lines : layout.label_lines) {
    if (layout.label_angle_rad == 0) {
      height = std::max(height, line * lines.size());
    } else {
      const double w = canvas.TextWidth(lines[0], layout.style.bar_label);
      height = std::max(
          height, w * std::sin(layout.label_angle_rad) + line * std::cos(layout.label_angle_rad));
    }
  }
  return height;
}

}  // namespace

void ValidateBarChart(const BarChart& chart) {
  const size_t bars = chart.values.size();
  if (bars == 0) throw UserError("BarChart has no bars: BarChart.values is empty");
  CheckSize(chart.labels.size(), bars, "labels");
  if (!chart.errors.empty()) CheckSize(chart.errors.size(), bars, "errors");
  if (!chart.colors.empty()) CheckSize(chart.colors.size(), bars, "colors");
  for (size_t i = 0; i < bars; ++i) {
    CheckFinite(chart.values[i], Indexed("values", i));
    if (!chart.errors.empty()) {
      CheckFinite(chart.errors[i], Indexed("errors", i));
      if (chart.errors[i] < 0) {
        throw UserError(Indexed("errors", i) + " is negative; it is a whisker half-length");
      }
    }
  }
  for (size_t i = 0; i < chart.colors.size(); ++i) {
    const Color& c = chart.colors[i];
    for (const double component : {c.r, c.g, c.b}) {
      if (!(component >= 0 && component <= 1)) {
        throw UserError(Indexed("colors", i) + " has a component outside [0, 1]");
      }
    }
  }
  for (size_t i = 0; i < chart.references.size(); ++i) {
    CheckFinite(chart.references[i].value, Indexed("references", i) + ".value");
  }
  if (chart.y_min) CheckFinite(*chart.y_min, "BarChart.y_min");
  if (chart.y_max) CheckFinite(*chart.y_max, "BarChart.y_max");
  if (chart.y_min && chart.y_max && !(*chart.y_min < *chart.y_max)) {
    throw UserError("BarChart.y_min must be below BarChart.y_max");
  }
}

BarLayout LayoutBarChart(Canvas& canvas, const BarChart& chart, int width, int height) {
  BarLayout layout;
  layout.style = Style::For(width, height);
  const Style& style = layout.style;
  layout.width = width;
  layout.height = height;
  layout.axis = FitAxis(chart);
  const size_t bars = chart.values.size();

  const double top = TitleBlockHeight(canvas, style, chart.title, chart.subtitle, width) +
                     canvas.LineHeight(style.value) / 2;
  const double right = style.pad + ReferenceMargin(canvas, style, chart.references);
  double left = YAxisMargin(canvas, style, layout.axis, chart.y_label);
  // Rotated labels reach left of their bar; widen the left margin until the first ones fit.
  for (int attempt = 0; attempt < 3; ++attempt) {
    const double slot = (width - left - right) / bars;
    LayoutLabels(canvas, chart, slot, layout);
    if (layout.label_angle_rad == 0) break;
    double overflow = 0;
    for (size_t i = 0; i < bars; ++i) {
      const double reach = canvas.TextWidth(layout.label_lines[i][0], style.bar_label) *
                           std::cos(layout.label_angle_rad);
      overflow = std::max(overflow, style.pad / 2 - (left + slot * (i + 0.5) - reach));
    }
    if (overflow <= 0.5) break;
    left += overflow;
  }
  const double bottom = style.pad + style.gap + LabelBlockHeight(canvas, layout);
  layout.plot = {left, top, width - left - right, height - top - bottom};
  const double slot = layout.plot.w / bars;
  layout.bar_width = slot * kBarFraction;
  for (size_t i = 0; i < bars; ++i) layout.center_x.push_back(left + slot * (i + 0.5));

  layout.value_font = style.value;
  double widest = 0;
  for (const double value : chart.values) {
    widest = std::max(widest, canvas.TextWidth(FormatValue(value, value), style.value));
  }
  if (widest > slot * 0.95) layout.value_font.size *= std::max(0.6, slot * 0.95 / widest);

  // Make room for value labels above (or below) the whiskers by adding whole ticks.
  const double label_room = style.gap + canvas.LineHeight(layout.value_font);
  AxisTicks& ticks = layout.axis.ticks;
  for (int attempt = 0; attempt < 8; ++attempt) {
    layout.baseline = std::clamp(0.0, ticks.lo, ticks.hi);
    bool grew = false;
    for (size_t i = 0; i < bars && !grew; ++i) {
      const double value = chart.values[i];
      if (value >= layout.baseline && !chart.y_max &&
          layout.axis.ToPixel(value + Error(chart, i), layout.plot) - label_room < layout.plot.y) {
        ticks.hi += ticks.step;
        ticks.values.push_back(ticks.hi);
        grew = true;
      } else if (value < layout.baseline && !chart.y_min &&
                 layout.axis.ToPixel(value - Error(chart, i), layout.plot) + label_room >
                     layout.plot.Bottom()) {
        ticks.lo -= ticks.step;
        ticks.values.insert(ticks.values.begin(), ticks.lo);
        grew = true;
      }
    }
    if (!grew) break;
  }
  return layout;
}

BarLayout LayoutBarChart(const BarChart& chart, int width, int height) {
  Canvas scratch(ImageFormat::kPng, 1, 1);
  return LayoutBarChart(scratch, chart, width, height);
}

}  // namespace recon::report
