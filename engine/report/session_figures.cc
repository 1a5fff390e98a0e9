#include "engine/report/session_figures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/report/html.h"

namespace recon::report {
namespace {

namespace fs = std::filesystem;

// Figures are drawn at twice the size they are shown at, so they stay sharp on high-DPI
// screens and when zoomed in; the chart style grows with the image, so they look the same.
constexpr int kDrawScale = 2;

using LossHistory = SessionReport::LossHistory;
using Rollout = SessionReport::Rollout;

std::string RunField(size_t index, const LossHistory& run, const std::string& field) {
  std::string name = "SessionReport.losses[" + std::to_string(index) + "]";
  if (!run.label.empty()) name += " ('" + run.label + "')";
  return name + "." + field;
}

// Adds the curve y(x) as the chart's next line, in the next palette colour. Non-finite values
// (a diverged loss, a beacon that was not seen) break the line instead of failing the figure:
// each finite stretch becomes a series of its own, named only once so the legend lists it once.
void AddCurve(LineChart& chart, int index, const std::string& name, const std::vector<double>& x,
              const std::vector<double>& y) {
  const size_t n = std::min(x.size(), y.size());
  LineChart::Series segment;
  segment.name = name;
  segment.color = PaletteColor(index);
  // Markers only help when points are few enough to tell apart.
  segment.markers = n <= 40;
  auto flush = [&] {
    if (segment.x.empty()) return;
    chart.series.push_back(segment);
    // A lone reading between gaps draws no line; its marker keeps it visible.
    if (segment.x.size() == 1) chart.series.back().markers = true;
    segment.x.clear();
    segment.y.clear();
    segment.name.clear();
  };
  for (size_t k = 0; k < n; ++k) {
    if (std::isfinite(x[k]) && std::isfinite(y[k])) {
      segment.x.push_back(x[k]);
      segment.y.push_back(y[k]);
    } else {
      flush();
    }
  }
  flush();
}

// Writes report_dir/figures/name.png and returns its path; errors name the file, since the
// chart library's own messages name only the chart field.
template <class Chart>
std::string WritePng(const Chart& chart, const std::string& report_dir, const std::string& name) {
  std::string path = (fs::path(report_dir) / "figures" / (name + ".png")).string();
  try {
    WriteChart(chart, path, kDrawScale * FigureFiles::kWidth, kDrawScale * FigureFiles::kHeight);
  } catch (const UserError& error) {
    // Write errors name the file already ("cannot write <path>: ..."); chart errors do not.
    const std::string what = error.what();
    if (what.find(path) != std::string::npos) throw;
    throw UserError("session report figure " + path + ": " + what);
  }
  return path;
}

bool HasPoints(const LineChart& chart) {
  for (const auto& series : chart.series) {
    if (!series.x.empty()) return true;
  }
  return false;
}

std::string Join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? separator : "") + parts[i];
  return out;
}

}  // namespace

Color InlierColor() { return PaletteColor(0); }
Color OutlierColor() { return PaletteColor(3); }
Color RowColor(int index) { return PaletteColor(index); }
Color Lighter(const Color& color) {
  return {0.45 * color.r + 0.55, 0.45 * color.g + 0.55, 0.45 * color.b + 0.55};
}

std::optional<LineChart> LossChart(const std::vector<LossHistory>& runs) {
  LineChart chart;
  chart.title = "Training losses";
  chart.x_label = "step";
  std::vector<std::string> labels;
  int curves = 0;
  for (size_t i = 0; i < runs.size(); ++i) {
    const LossHistory& run = runs[i];
    const std::pair<const char*, const std::vector<double>*> terms[] = {
        {"total", &run.total_loss},
        {"action", &run.action_loss},
        {"beacon", &run.beacon_loss},
        {"play", &run.play_loss}};
    for (const auto& [term, values] : terms) {
      if (values->empty()) continue;
      if (values->size() != run.step.size()) {
        throw UserError(RunField(i, run, std::string(term) + "_loss") + " has " +
                        std::to_string(values->size()) + " entries but step has " +
                        std::to_string(run.step.size()));
      }
      AddCurve(chart, curves++, run.label + " " + term, run.step, *values);
    }
    labels.push_back(run.label);
  }
  if (!HasPoints(chart)) return std::nullopt;
  // Squared errors span decades and read best on a log axis; negative log-likelihoods (the
  // paper's loss) go below zero, which a log axis cannot show.
  chart.log_y = true;
  for (const LineChart::Series& series : chart.series) {
    for (double v : series.y) chart.log_y = chart.log_y && (!std::isfinite(v) || v > 0);
  }
  chart.y_label = chart.log_y ? "loss (log scale)" : "loss";
  chart.subtitle = Join(labels, " vs ") + "; one line per run and loss term";
  return chart;
}

std::optional<LineChart> BeaconTraceChart(const SessionReport::BeaconTrace& trace) {
  LineChart chart;
  chart.title = trace.episode + ": beacon \"" + trace.beacon + "\"";
  if (!trace.object.empty()) chart.subtitle = "marks " + trace.object;
  const bool seconds = trace.step_seconds > 0 && std::isfinite(trace.step_seconds);
  chart.x_label = seconds ? "time (s)" : "step";
  chart.y_label = trace.unit.empty() ? "reading" : "reading (" + trace.unit + ")";
  for (size_t c = 0; c < trace.values.size(); ++c) {
    const std::vector<double>& y = trace.values[c];
    std::vector<double> x(y.size());
    for (size_t k = 0; k < y.size(); ++k) {
      x[k] = seconds ? static_cast<double>(k) * trace.step_seconds : static_cast<double>(k);
    }
    const std::string name = c < trace.component_names.size() && !trace.component_names[c].empty()
                                 ? trace.component_names[c]
                                 : "component " + std::to_string(c + 1);
    AddCurve(chart, static_cast<int>(c), name, x, y);
  }
  if (!HasPoints(chart)) return std::nullopt;
  return chart;
}

std::optional<BarChart> CalibrationChart(const SessionReport::Calibration& calibration) {
  const auto& residual = calibration.residual_m;
  const auto& inlier = calibration.inlier;
  if (!inlier.empty() && inlier.size() != residual.size()) {
    throw UserError("SessionReport.calibration.inlier has " + std::to_string(inlier.size()) +
                    " entries but residual_m has " + std::to_string(residual.size()));
  }
  // Millimetres: residuals are centimetre-sized, and the bar labels of metres would round
  // them to two digits.
  constexpr double kMm = 1000;
  BarChart chart;
  chart.title = "Calibration residuals";
  chart.y_label = "residual (mm)";
  int outliers = 0;
  for (size_t i = 0; i < residual.size(); ++i) {
    if (!std::isfinite(residual[i])) continue;
    const bool is_inlier = inlier.empty() || inlier[i];
    outliers += !is_inlier;
    chart.labels.push_back(std::to_string(i + 1));
    chart.values.push_back(kMm * residual[i]);
    chart.colors.push_back(is_inlier ? InlierColor() : OutlierColor());
  }
  if (chart.values.empty()) return std::nullopt;
  chart.subtitle = std::to_string(chart.values.size()) + " points, " + std::to_string(outliers) +
                   (outliers == 1 ? " outlier" : " outliers") +
                   " (vermillion); bars are numbered by calibration point";
  if (std::isfinite(calibration.threshold_m)) {
    chart.references.push_back(
        {kMm * calibration.threshold_m,
         "threshold " + FormatFixed(kMm * calibration.threshold_m, 0) + " mm"});
  }
  if (std::isfinite(calibration.rmse_m)) {
    chart.references.push_back(
        {kMm * calibration.rmse_m, "RMSE " + FormatFixed(kMm * calibration.rmse_m, 1) + " mm"});
  }
  chart.y_min = 0;
  return chart;
}

std::vector<BarChart> RolloutMetricCharts(const std::vector<Rollout>& rollouts) {
  std::vector<BarChart> charts;
  std::vector<std::string> metrics;
  for (const Rollout& rollout : rollouts) {
    bool seen = false;
    for (const auto& metric : metrics) seen = seen || metric == rollout.metric_name;
    if (!seen) metrics.push_back(rollout.metric_name);
  }
  for (const std::string& metric : metrics) {
    BarChart chart;
    chart.title = metric.empty() ? "Rollout metric" : metric;
    chart.y_label = metric.empty() ? "metric" : metric;
    std::vector<std::string> tests;
    bool higher_is_better = false;
    for (size_t i = 0; i < rollouts.size(); ++i) {
      const Rollout& rollout = rollouts[i];
      if (rollout.metric_name != metric || !std::isfinite(rollout.metric_mean)) continue;
      chart.labels.push_back(rollout.label);
      chart.values.push_back(rollout.metric_mean);
      const double sem = rollout.metric_sem;
      chart.errors.push_back(std::isfinite(sem) && sem > 0 ? sem : 0);
      chart.colors.push_back(RowColor(static_cast<int>(i)));
      tests.push_back(std::to_string(rollout.tests));
      higher_is_better = rollout.higher_is_better;
    }
    if (chart.values.empty()) continue;
    chart.subtitle = "mean \u00b1 standard error; tests per bar: " + Join(tests, ", ") + "; " +
                     (higher_is_better ? "higher" : "lower") + " is better";
    charts.push_back(std::move(chart));
  }
  return charts;
}

std::optional<BarChart> RolloutSuccessChart(const std::vector<Rollout>& rollouts) {
  BarChart chart;
  chart.title = "Success rate";
  chart.subtitle = "mean \u00b1 standard error over the test scenarios";
  chart.y_label = "success rate (%)";
  for (size_t i = 0; i < rollouts.size(); ++i) {
    const Rollout& rollout = rollouts[i];
    if (!rollout.has_success || !std::isfinite(rollout.success_rate)) continue;
    chart.labels.push_back(rollout.label);
    chart.values.push_back(100 * rollout.success_rate);
    const double sem = rollout.success_sem;
    chart.errors.push_back(std::isfinite(sem) && sem > 0 ? 100 * sem : 0);
    chart.colors.push_back(RowColor(static_cast<int>(i)));
  }
  if (chart.values.empty()) return std::nullopt;
  chart.y_min = 0;
  chart.y_max = 100;
  return chart;
}

std::optional<BarChart> TeachingTimeChart(const std::vector<SessionReport::LedgerRow>& ledger) {
  BarChart chart;
  chart.title = "Teaching time";
  chart.y_label = "total teaching time (s)";
  bool any_paper = false;
  for (size_t i = 0; i < ledger.size(); ++i) {
    const auto& row = ledger[i];
    if (!std::isfinite(row.total_s)) continue;
    const Color color = RowColor(static_cast<int>(i));
    chart.labels.push_back(row.label);
    chart.values.push_back(row.total_s);
    chart.colors.push_back(color);
    if (row.paper_total_s && std::isfinite(*row.paper_total_s)) {
      any_paper = true;
      chart.labels.push_back("paper: " + row.label);
      chart.values.push_back(*row.paper_total_s);
      chart.colors.push_back(Lighter(color));
    }
  }
  if (chart.values.empty()) return std::nullopt;
  chart.y_min = 0;  // bar lengths must compare as times do
  chart.subtitle = any_paper ? "measured here, each followed by the paper's total (lighter bar)"
                             : "measured here (the paper gives no totals for these rows)";
  return chart;
}

FigureFiles::FigureFiles(std::string report_dir) : report_dir_(std::move(report_dir)) {}

std::string FigureFiles::Add(const BarChart& chart, const std::string& name,
                             const std::string& caption_html) {
  return Embed(WritePng(chart, report_dir_, name), chart.title, caption_html);
}

std::string FigureFiles::Add(const LineChart& chart, const std::string& name,
                             const std::string& caption_html) {
  return Embed(WritePng(chart, report_dir_, name), chart.title, caption_html);
}

std::string FigureFiles::Add(const HeatMap& chart, const std::string& name,
                             const std::string& caption_html) {
  return Embed(WritePng(chart, report_dir_, name), chart.title, caption_html);
}

std::string FigureFiles::Embed(const std::string& path, const std::string& title,
                               const std::string& caption_html) {
  written_.push_back(path);
  const std::string file = "figures/" + fs::path(path).filename().string();
  const std::optional<std::string> bytes = ReadWholeFile(path);
  if (!bytes) throw UserError("cannot read back the figure " + path);
  return "<figure><img src=\"" + PngDataUri(*bytes) + "\" width=\"" + std::to_string(kWidth) +
         "\" height=\"" + std::to_string(kHeight) + "\" alt=\"" + EscapeHtml(title) +
         "\" data-file=\"" + EscapeHtml(file) + "\">\n<figcaption>" + caption_html +
         "</figcaption></figure>\n";
}

void FigureFiles::RemoveStale() const {
  std::set<std::string> keep;
  for (const auto& path : written_) keep.insert(fs::path(path).filename().string());
  std::vector<fs::path> stale;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(report_dir_) / "figures", ec)) {
    const fs::path& path = entry.path();
    if (path.extension() == ".png" && entry.is_regular_file(ec) &&
        !keep.count(path.filename().string())) {
      stale.push_back(path);
    }
  }
  // Best effort: a stale figure is untidy, not wrong, so failing to remove it is no error.
  for (const fs::path& path : stale) fs::remove(path, ec);
}

}  // namespace recon::report
