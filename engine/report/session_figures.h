#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/report/chart.h"
#include "engine/report/heat_map.h"
#include "engine/report/session_report.h"

namespace recon::report {

// The charts of the session report, built from its data. Kept apart from the HTML so that the
// choice of what each figure shows is in one place. Each builder returns nothing when there is
// nothing drawable (no data, or only NaN/infinite values, which are left out rather than
// failing the whole report: a diverged run is exactly what a reader needs to see).

/// Log-y loss curves, x = step: one series per run and loss term present. Throws UserError
/// naming the field when a term's length differs from `step`.
std::optional<LineChart> LossChart(const std::vector<SessionReport::LossHistory>& runs);

/// One series per component, x in seconds (or steps when step_seconds is 0).
std::optional<LineChart> BeaconTraceChart(const SessionReport::BeaconTrace& trace);

/// One bar per calibration point, inliers and outliers coloured apart, dashed lines at the
/// threshold and the RMSE. Throws UserError when `inlier` and `residual_m` differ in length.
std::optional<BarChart> CalibrationChart(const SessionReport::Calibration& calibration);

/// Metric mean +- standard error per rollout; one chart per distinct metric_name, in order of
/// first appearance, because bars of different metrics cannot share an axis.
std::vector<BarChart> RolloutMetricCharts(const std::vector<SessionReport::Rollout>& rollouts);

/// Success rate (%) +- standard error of the rollouts that report one.
std::optional<BarChart> RolloutSuccessChart(const std::vector<SessionReport::Rollout>& rollouts);

/// Total teaching time per ledger row, each followed by a lighter "paper: ..." bar when the
/// paper gives a total for that row.
std::optional<BarChart> TeachingTimeChart(const std::vector<SessionReport::LedgerRow>& ledger);

/// Writes the report's charts as PNG files into report_dir/figures/ and returns the HTML that
/// embeds each one, so the page and the files always hold the same bytes.
class FigureFiles {
 public:
  /// Size a figure is shown at in the page, in CSS pixels; the PNG has twice as many. Every
  /// figure has the chart library's 16:9 reference shape, so fonts match across figures.
  static constexpr int kWidth = 960;
  static constexpr int kHeight = 540;

  explicit FigureFiles(std::string report_dir);

  /// Writes `chart` as figures/`name`.png and returns a <figure> with the PNG embedded as a data:
  /// URI and `caption_html` under it. UserError naming the file if it cannot be written or the
  /// chart is malformed.
  std::string Add(const BarChart& chart, const std::string& name, const std::string& caption_html);
  std::string Add(const LineChart& chart, const std::string& name, const std::string& caption_html);
  std::string Add(const HeatMap& chart, const std::string& name, const std::string& caption_html);

  /// Removes PNGs in figures/ that were not written by this object: left by an earlier report
  /// with more figures, they would otherwise pass for part of this one.
  void RemoveStale() const;

  /// Paths of the files written, in order.
  const std::vector<std::string>& written() const { return written_; }

 private:
  std::string Embed(const std::string& path, const std::string& title,
                    const std::string& caption_html);

  std::string report_dir_;
  std::vector<std::string> written_;
};

/// The colours of calibration inliers and outliers (the HTML legend shows them too).
Color InlierColor();
Color OutlierColor();
/// The colour of the i-th rollout or ledger row, the same in every figure.
Color RowColor(int index);
/// `color` blended towards white, for the paper's bars next to measured ones.
Color Lighter(const Color& color);

}  // namespace recon::report
