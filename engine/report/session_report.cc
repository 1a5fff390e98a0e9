// The session report page: one section per part of the data, each with its figures and the
// table that carries the numbers; what each figure shows is decided in session_figures.cc.
#include "engine/report/session_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include "engine/core/files.h"
#include "engine/report/html.h"
#include "engine/report/session_figures.h"

namespace recon::report {
namespace {

using Rows = std::vector<std::vector<std::string>>;

// Inline so the page needs nothing else. The ink avoids the chart palette, so figures stand
// out from the page chrome (the browser test relies on that too).
constexpr const char* kStyle = R"css(
:root { color-scheme: light; }
* { box-sizing: border-box; }
body { margin: 0; background: #fff; color: #1f2328;
  font: 15px/1.55 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial,
    "DejaVu Sans", sans-serif; }
main { max-width: 1000px; margin: 0 auto; padding: 28px 20px 40px; }
header { border-bottom: 3px solid #1f2937; padding-bottom: 12px; }
h1 { font-size: 28px; line-height: 1.2; margin: 0 0 8px; }
h2 { font-size: 21px; margin: 0 0 10px; }
.meta { color: #57606a; margin: 2px 0; }
code { font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace;
  font-size: 0.88em; background: #f0f2f4; border-radius: 4px; padding: 1px 5px; }
section { border-top: 1px solid #d0d7de; margin-top: 30px; padding-top: 18px; }
section#overview { border-top: none; margin-top: 12px; }
nav ol { margin: 6px 0 0; padding-left: 22px; }
nav a { color: #1f2937; font-weight: 600; }
.status { color: #57606a; }
figure { margin: 14px 0 16px; }
figure img { display: block; width: 100%; height: auto; border: 1px solid #e5e7eb; }
figcaption { color: #57606a; font-size: 13px; margin-top: 6px; }
table { border-collapse: collapse; width: 100%; margin: 10px 0 14px; font-size: 14px; }
th, td { border: 1px solid #d0d7de; padding: 6px 10px; text-align: left; vertical-align: top; }
th { background: #f0f2f4; font-weight: 600; }
tbody tr:nth-child(even) td { background: #f9fafb; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
.missing { background: #fff8e6; border-left: 4px solid #b7791f; padding: 10px 14px; }
.note { color: #57606a; font-size: 14px; }
.badge { display: inline-block; border-radius: 4px; padding: 0 8px; color: #fff;
  font-weight: 700; letter-spacing: 0.04em; }
.pass { background: #1a7f37; }
.fail { background: #b42318; }
.swatch { display: inline-block; width: 12px; height: 12px; border-radius: 2px;
  vertical-align: -1px; margin: 0 4px 0 8px; }
footer { margin-top: 36px; border-top: 1px solid #d0d7de; padding-top: 10px; color: #57606a;
  font-size: 13px; }
)css";

std::string Text(const std::string& text) { return EscapeHtml(text); }
std::string Code(const std::string& command) { return "<code>" + Text(command) + "</code>"; }
std::string Meters(double value) {
  return std::isfinite(value) ? FormatFixed(value, 3) + " m" : "n/a";
}
std::string Percent(double fraction) {
  return std::isfinite(fraction) ? FormatFixed(100 * fraction, 0) + "%" : "n/a";
}
// "1 run", "2 runs".
std::string Count(size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}
std::string Swatch(const Color& color) {
  return "<span class=\"swatch\" style=\"background:" + CssColor(color) + "\"></span>";
}

std::string Seconds(double value) {
  if (!std::isfinite(value)) return "n/a";
  if (std::abs(value) < 60) return FormatFixed(value, 1) + " s";
  const long total = std::lround(std::abs(value));
  const std::string minutes = std::to_string(total / 60);
  const std::string seconds = (total % 60 < 10 ? "0" : "") + std::to_string(total % 60);
  return FormatFixed(value, 0) + " s (" + (value < 0 ? "-" : "") + minutes + ":" + seconds + ")";
}

// What a reader sees instead of a section's content: what is missing and how to get it.
std::string Missing(const std::string& what, const std::string& command_html) {
  return "<p class=\"missing\">" + Text(what) + ": " + command_html + ".</p>\n";
}

// A result that no longer matches the session, said where the result is shown.
std::string OutOfDate(const std::string& label, const std::string& why) {
  if (why.empty()) return "";
  return "<p class=\"missing\"><strong>Out of date:</strong> " + Text(label) + ": " + Text(why) +
         ".</p>\n";
}

std::string Note(const std::string& text) {
  return text.empty() ? "" : "<p class=\"note\">" + Text(text) + "</p>\n";
}

// The last finite value of a column, so a run that diverged at the end still shows where it
// was; NaN (shown "n/a") when there is none.
double LastFinite(const std::vector<double>& values) {
  for (auto it = values.rbegin(); it != values.rend(); ++it) {
    if (std::isfinite(*it)) return *it;
  }
  return NAN;
}

size_t CountNonFinite(const std::vector<double>& values) {
  size_t count = 0;
  for (const double value : values) count += !std::isfinite(value);
  return count;
}

// A file-name-safe version of `text` (letters, digits, '-'; the rest become '_').
std::string Slug(const std::string& text) {
  std::string out;
  for (const char c : text) {
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  }
  return out.empty() ? "unnamed" : out.substr(0, 40);
}

struct Part {
  std::string id, heading, status, body;
};

Part Overview(const SessionReport& report) {
  Part part{"overview", "Overview", "", ""};
  if (report.facts.empty()) {
    part.body =
        Missing("No session facts", "record a session with " + Code("recon record --session DIR") +
                                        " and build the report from it");
    return part;
  }
  Rows rows;
  for (const auto& [key, value] : report.facts) rows.push_back({Text(key), Text(value)});
  part.body = HtmlTable({"Item", "Value"}, rows);
  return part;
}

Part Losses(const SessionReport& report, FigureFiles& figures) {
  Part part{"losses", "Training losses", "", ""};
  const std::optional<LineChart> chart = LossChart(report.losses);
  if (!chart) {
    part.status = "missing";
    part.body = Missing("No training yet", "run " + Code("recon train --session DIR"));
    return part;
  }
  part.status = Count(report.losses.size(), "run", "runs");
  part.body = figures.Add(
      *chart, "losses",
      std::string("Loss per optimiser step") +
          (chart->log_y ? " on a log scale" : " (negative log-likelihoods go below zero)") +
          "; terms a run does not train (e.g. the Baseline's beacon and play "
          "heads) are absent.");
  Rows rows;
  for (const auto& run : report.losses) {
    auto last = [](const std::vector<double>& column) {
      return column.empty() ? std::string("&mdash;") : FormatNumber(LastFinite(column));
    };
    size_t bad = 0;
    for (const auto* column :
         {&run.action_loss, &run.beacon_loss, &run.play_loss, &run.total_loss}) {
      bad += CountNonFinite(*column);
    }
    std::string note = Text(run.note);
    if (bad > 0) {
      note += (note.empty() ? "" : "; ") + std::to_string(bad) + " NaN/infinite values not drawn";
    }
    rows.push_back({Text(run.label), FormatNumber(LastFinite(run.step)), last(run.total_loss),
                    last(run.action_loss), last(run.beacon_loss), last(run.play_loss), note});
  }
  for (const auto& run : report.losses) part.body += OutOfDate(run.label, run.out_of_date);
  part.body += HtmlTable({"Run", "Last step", "Total", "Action", "Beacon", "Play", "Note"}, rows,
                         {1, 2, 3, 4, 5});
  part.body += Note("Loss columns show the last logged value of each term.");
  return part;
}

Part Beacons(const SessionReport& report, FigureFiles& figures) {
  Part part{"beacons", "Beacon traces", "", ""};
  Rows rows;
  for (size_t i = 0; i < report.beacon_traces.size(); ++i) {
    const auto& trace = report.beacon_traces[i];
    const std::optional<LineChart> chart = BeaconTraceChart(trace);
    size_t readings = 0;
    std::string ranges;
    for (size_t c = 0; c < trace.values.size(); ++c) {
      const auto& column = trace.values[c];
      readings = std::max(readings, column.size());
      double lo = INFINITY, hi = -INFINITY;
      for (const double v : column) lo = std::isfinite(v) ? std::min(lo, v) : lo;
      for (const double v : column) hi = std::isfinite(v) ? std::max(hi, v) : hi;
      const std::string name =
          c < trace.component_names.size() ? trace.component_names[c] : std::to_string(c + 1);
      ranges += (c ? "<br>" : "") + Text(name) + ": " +
                (lo <= hi ? FormatNumber(lo) + " to " + FormatNumber(hi) + " " + Text(trace.unit)
                          : "no readings");
    }
    if (chart) {
      const std::string name =
          "beacon_" + std::to_string(i + 1) + "_" + Slug(trace.episode) + "_" + Slug(trace.beacon);
      part.body += figures.Add(*chart, name,
                               "Beacon " + Code(trace.beacon) + " in episode " +
                                   Code(trace.episode) + "; gaps are missing readings.");
    }
    const double duration = trace.step_seconds > 0 ? trace.step_seconds * readings : NAN;
    rows.push_back({Text(trace.episode), Text(trace.beacon), Text(trace.object),
                    std::to_string(readings),
                    std::isfinite(duration) ? Seconds(duration) : "&mdash;", ranges});
  }
  if (part.body.empty()) {
    part.status = "missing";
    part.body = Missing(
        "No beacon readings in this session",
        "place beacons and record demonstrations with " + Code("recon record --session DIR"));
    return part;
  }
  part.status = Count(report.beacon_traces.size(), "trace", "traces");
  part.body +=
      HtmlTable({"Episode", "Beacon", "Marks", "Readings", "Duration", "Range"}, rows, {3, 4});
  return part;
}

Part CalibrationPart(const SessionReport& report, FigureFiles& figures) {
  Part part{"calibration", "Calibration residuals", "", ""};
  const auto& cal = report.calibration;
  if (!cal.present) {
    part.status = "missing";
    part.body = Missing("No calibration in this session",
                        "run " + Code("recon calibrate --sim --out cal.json") + " and " +
                            Code("recon record ... --calibration cal.json"));
    return part;
  }
  const std::string badge = cal.passed ? "<span class=\"badge pass\">PASS</span>"
                                       : "<span class=\"badge fail\">FAIL</span>";
  part.status = cal.passed ? "PASS" : "FAIL";
  size_t outliers = 0;
  for (size_t i = 0; i < cal.inlier.size(); ++i) outliers += !cal.inlier[i];
  if (const std::optional<BarChart> chart = CalibrationChart(cal)) {
    part.body =
        figures.Add(*chart, "calibration",
                    "Residual of each calibration point after the fit:" + Swatch(InlierColor()) +
                        "inlier" + Swatch(OutlierColor()) +
                        "outlier (left out of the fit); dashed lines mark the RMSE and "
                        "the pass threshold.");
  } else {
    part.body = Note("The calibration stores no per-point residuals.");
  }
  const std::string verdict =
      badge + (cal.passed ? " RMSE &le; threshold" : " RMSE &gt; threshold");
  part.body += HtmlTable(
      {"Points", "Outliers", "RMSE", "Mean", "Median", "95th percentile", "Threshold", "Result"},
      {{std::to_string(cal.residual_m.size()), std::to_string(outliers), Meters(cal.rmse_m),
        Meters(cal.mean_m), Meters(cal.median_m), Meters(cal.p95_m), Meters(cal.threshold_m),
        verdict}},
      {0, 1, 2, 3, 4, 5, 6});
  return part;
}

Part Rollouts(const SessionReport& report, FigureFiles& figures) {
  Part part{"rollouts", "Simulated rollouts: Baseline vs RECON", "", ""};
  if (report.rollouts.empty()) {
    part.status = "missing";
    part.body = Missing("No rollouts yet", "run " + Code("recon eval --session DIR"));
    return part;
  }
  part.status = Count(report.rollouts.size(), "policy", "policies");
  part.body =
      "<p>Each trained policy was rolled out in the simulated cell with the beacons removed.</p>\n";
  for (const auto& rollout : report.rollouts) {
    part.body += OutOfDate(rollout.label + " rollouts", rollout.out_of_date);
  }
  const std::vector<BarChart> metric_charts = RolloutMetricCharts(report.rollouts);
  for (size_t i = 0; i < metric_charts.size(); ++i) {
    part.body += figures.Add(metric_charts[i], "rollouts_metric_" + std::to_string(i + 1),
                             "Bars show the mean over the test scenarios; whiskers the standard "
                             "error.");
  }
  if (const std::optional<BarChart> chart = RolloutSuccessChart(report.rollouts)) {
    part.body += figures.Add(*chart, "rollouts_success",
                             "Share of test scenarios solved; whiskers show the standard error.");
  }
  Rows rows;
  for (const auto& rollout : report.rollouts) {
    std::string details;
    for (const auto& [key, value] : rollout.details) {
      details += (details.empty() ? "" : "<br>") + Text(key) + ": " + FormatNumber(value);
    }
    rows.push_back(
        {Text(rollout.label), Text(rollout.metric_name),
         FormatNumber(rollout.metric_mean) + " &plusmn; " + FormatNumber(rollout.metric_sem),
         rollout.higher_is_better ? "higher" : "lower", std::to_string(rollout.tests),
         rollout.has_success
             ? Percent(rollout.success_rate) + " &plusmn; " + Percent(rollout.success_sem)
             : "&mdash;",
         details, Text(rollout.note)});
  }
  part.body += HtmlTable(
      {"Policy", "Metric", "Mean \u00b1 SEM", "Better", "Tests", "Success", "Details", "Note"},
      rows, {2, 4, 5});
  return part;
}

Part RealTrialsPart(const SessionReport& report) {
  Part part{"real-trials", "Trials on the real arm", "", ""};
  size_t trials = 0;
  for (const auto& method : report.real_trials) trials += method.trials.size();
  part.status = Count(trials, "trial", "trials");
  part.body =
      "<p>Each trial: a person set the test scene's layout up, the policy drove the arm with the "
      "beacons removed, and the person judged it.</p>\n";
  Rows summary, rows;
  for (const auto& method : report.real_trials) {
    part.body += OutOfDate(method.label + " trials", method.out_of_date);
    const double rate =
        method.trials.empty() ? 0.0 : double(method.successes) / method.trials.size();
    // The same scenes in simulation, where the session was rolled out there too: sim to real.
    int simulated = 0, simulated_successes = 0;
    for (const auto& t : method.trials) {
      if (!t.simulated_succeeded) continue;
      ++simulated;
      if (*t.simulated_succeeded) ++simulated_successes;
    }
    summary.push_back(
        {Text(method.label), Text(method.cell.empty() ? "real" : method.cell),
         std::to_string(method.successes) + " of " + std::to_string(method.trials.size()),
         Percent(rate),
         simulated == 0
             ? "-"
             : std::to_string(simulated_successes) + " of " + std::to_string(simulated)});
    for (const auto& t : method.trials) {
      rows.push_back({Text(method.label), std::to_string(t.number),
                      t.succeeded ? "success" : "failure", Text(t.reason),
                      t.stopped ? "stopped by the person" : "ran its time", std::to_string(t.steps),
                      Seconds(t.seconds),
                      !t.simulated_succeeded   ? "-"
                      : *t.simulated_succeeded ? "success"
                                               : "failure"});
    }
  }
  part.body += HtmlTable({"Policy", "Cell", "Succeeded", "Success", "Same scenes, simulated"},
                         summary, {2, 3, 4});
  part.body += HtmlTable(
      {"Policy", "Trial", "Verdict", "Why", "End", "Steps", "Time", "Same scene, simulated"}, rows,
      {1, 5, 6});
  return part;
}

Part ProbePart(const SessionReport& report, FigureFiles& figures) {
  Part part{"probe", "What the policies look at", "", ""};
  if (!report.probe) {
    part.status = "missing";
    part.body = Missing("Not probed yet", "run " + Code("recon eval --session DIR --probe"));
    return part;
  }
  const SessionReport::Probe& probe = *report.probe;
  part.status = probe.maps.empty()
                    ? "read out on recorded frames"
                    : Count(probe.maps.size() + probe.outcome_maps.size(), "heat map", "heat maps");
  const bool outcomes = std::any_of(probe.rows.begin(), probe.rows.end(),
                                    [](const auto& row) { return row.success_rate.has_value(); });
  part.body = OutOfDate("The probe", probe.out_of_date);
  if (!probe.maps.empty()) {
    part.body +=
        "<p>Each object was moved over a grid of table places with everything else held, "
        "and each policy's first action and features were compared with the scene as it "
        "was. A policy that confuses the bowl with the plate moves with the bowl. The "
        "read-out fits each object's position from the features on other test scenes "
        "(R<sup>2</sup> 1: the features encode it; 0: not at all).";
    if (outcomes) {
      part.body +=
          " Each policy was also rolled out whole from every place: does it still do "
          "the task with the object there?";
    }
    part.body += "</p>\n";
  } else {
    part.body +=
        "<p>This session was taught on a real cell, which cannot be simulated, so nothing was "
        "moved. The read-out fits each beacon's reading from the features on the recorded "
        "frames and scores it on whole episodes it was not fitted on (R<sup>2</sup> 1: the "
        "features encode the object; 0: not at all).</p>\n";
  }
  std::string verdicts;
  for (const std::string& verdict : probe.verdicts) verdicts += "<li>" + Text(verdict) + "</li>";
  if (!verdicts.empty()) part.body += "<ul>" + verdicts + "</ul>\n";
  const auto number = [](const std::optional<double>& v) {
    return v ? FormatNumber(*v) : std::string("&mdash;");
  };
  Rows rows;
  for (const auto& row : probe.rows) {
    rows.push_back({Text(row.label), Text(row.object), number(row.action_change_per_10cm),
                    number(row.feature_change_per_10cm),
                    row.readout_r2 ? FormatFixed(*row.readout_r2, 2) : "&mdash;"});
    if (outcomes) {
      rows.back().push_back(row.success_rate ? FormatFixed(100 * *row.success_rate, 0) + " %"
                                             : "&mdash;");
    }
  }
  std::vector<std::string> header = {"Policy", "Object moved", "Action change per 10 cm",
                                     "Feature change per 10 cm", "Read-out R\u00b2"};
  std::set<size_t> numeric = {2, 3, 4};
  if (outcomes) {
    header.push_back("Rollouts succeeded");
    numeric.insert(5);
  }
  part.body += HtmlTable(header, rows, numeric);
  part.body += Note(probe.note);
  for (const HeatMap& map : probe.maps) {
    part.body += figures.Add(map, "probe_" + Slug(map.title),
                             Text(map.title) +
                                 ": how much the action changes with the object "
                                 "placed in each cell (blank: it would overlap "
                                 "another object); seen from behind the robot.");
  }
  for (const HeatMap& map : probe.outcome_maps) {
    part.body += figures.Add(map, "probe_" + Slug(map.title),
                             Text(map.title) +
                                 ": where the whole rollout succeeded (bright) or failed (dark) "
                                 "with the object placed in each cell (blank: it would overlap "
                                 "another object, or the arm could not reach the task); seen "
                                 "from behind the robot.");
  }
  return part;
}

Part TeachingTime(const SessionReport& report, FigureFiles& figures) {
  Part part{"teaching-time", "Teaching time", "", ""};
  if (report.ledger.empty()) {
    part.status = "missing";
    part.body = Missing("No teaching time logged yet",
                        "record demonstrations, beacon placements and play with " +
                            Code("recon record --session DIR"));
    return part;
  }
  part.status = Count(report.ledger.size(), "way of teaching", "ways of teaching");
  if (const std::optional<BarChart> chart = TeachingTimeChart(report.ledger)) {
    part.body = figures.Add(*chart, "teaching_time",
                            "Total time a person spent teaching, per way of teaching; lighter "
                            "bars give the paper's total for the same row.");
  }
  Rows rows;
  for (const auto& row : report.ledger) {
    std::string paper = "&mdash;", difference = "&mdash;";
    if (row.paper_total_s) {
      paper = Seconds(*row.paper_total_s);
      const double delta = row.total_s - *row.paper_total_s;
      difference = (delta >= 0 ? "+" : "&minus;") + Seconds(std::abs(delta));
    }
    rows.push_back({Text(row.label), Seconds(row.demonstrations_s),
                    Seconds(row.beacon_placements_s), Seconds(row.play_s),
                    "<strong>" + Seconds(row.total_s) + "</strong>", paper, difference});
  }
  part.body += HtmlTable({"Way of teaching", "Demonstrations", "Beacon placements", "Play", "Total",
                          "Paper total", "Total vs paper"},
                         rows, {1, 2, 3, 4, 5, 6});
  part.body += Note(report.ledger_note);
  return part;
}

std::string Page(const SessionReport& report, const std::vector<Part>& parts) {
  const std::string title = Text(report.title.empty() ? "Teaching session report" : report.title);
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += "<title>" + title + "</title>\n<style>" + kStyle + "</style>\n</head>\n";
  html += "<body>\n<main>\n<header>\n<h1>" + title + "</h1>\n";
  if (!report.session_path.empty()) {
    html += "<p class=\"meta\">Session " + Code(report.session_path) + "</p>\n";
  }
  if (!report.generated.empty()) {
    html += "<p class=\"meta\">Generated " + Text(report.generated) + "</p>\n";
  }
  html += "<nav><ol>\n";
  for (const Part& part : parts) {
    html += "<li><a href=\"#" + part.id + "\">" + Text(part.heading) + "</a>";
    if (!part.status.empty()) {
      html += " <span class=\"status\">&middot; " + Text(part.status) + "</span>";
    }
    html += "</li>\n";
  }
  html += "</ol></nav>\n</header>\n";
  for (const Part& part : parts) {
    html += "<section id=\"" + part.id + "\">\n<h2>" + Text(part.heading) + "</h2>\n" + part.body +
            "</section>\n";
  }
  html += "<footer>Written by RECON Studio. Every figure is embedded in this file and also saved ";
  html += "as a PNG in <code>figures/</code> next to it.</footer>\n";
  return html + "</main>\n</body>\n</html>\n";
}

}  // namespace

std::vector<std::string> WriteSessionReport(const SessionReport& report,
                                            const std::string& out_dir) {
  // Fails before any drawing when the folder cannot be used; names the folder.
  EnsureWritableDirectory(out_dir);
  EnsureWritableDirectory((std::filesystem::path(out_dir) / "figures").string());
  FigureFiles figures(out_dir);
  std::vector<Part> parts;
  parts.push_back(Overview(report));
  parts.push_back(Losses(report, figures));
  parts.push_back(Beacons(report, figures));
  parts.push_back(CalibrationPart(report, figures));
  parts.push_back(Rollouts(report, figures));
  if (!report.real_trials.empty()) parts.push_back(RealTrialsPart(report));
  parts.push_back(ProbePart(report, figures));
  parts.push_back(TeachingTime(report, figures));
  const std::string html_path = (std::filesystem::path(out_dir) / "report.html").string();
  WriteFileAtomically(html_path, Page(report, parts));
  figures.RemoveStale();
  std::vector<std::string> written = figures.written();
  written.push_back(html_path);
  return written;
}

}  // namespace recon::report
