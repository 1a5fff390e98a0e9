#include "engine/experiments/summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "engine/core/files.h"
#include "engine/core/machine.h"
#include "engine/core/stats.h"
#include "engine/report/chart.h"

namespace recon::experiments {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string ResultsCsv(const std::vector<RunResult>& runs, bool has_success) {
  // Each run's outcome details (World::OutcomeDetails: grasped, closest_approach_m, ...) as
  // columns: the means in summary.json hide whether a run failed in every scene or in a few.
  std::set<std::string> detail_keys;
  for (const RunResult& r : runs) {
    for (const auto& [key, value] : r.details) detail_keys.insert(key);
  }
  std::ostringstream csv;
  // No wall-clock time here: the same runs give the same bytes on any machine (timing.csv).
  csv << "condition,demos,run,data_seed,train_seed,metric,attempts,train_steps,"
         "final_action_loss,final_beacon_loss,final_play_loss,final_consistency_loss"
      << (has_success ? ",success_rate" : "");
  for (const std::string& key : detail_keys) csv << "," << key;
  csv << "\n";
  char buf[512];
  for (const RunResult& r : runs) {
    std::snprintf(buf, sizeof(buf), "%s,%d,%d,%llu,%llu,%.6f,%d,%d,%.6g,%.6g,%.6g,%.6g",
                  r.condition.c_str(), r.demos, r.run, static_cast<unsigned long long>(r.data_seed),
                  static_cast<unsigned long long>(r.train_seed), r.metric, r.attempts,
                  r.train_steps, r.final_losses.action_loss, r.final_losses.beacon_loss,
                  r.final_losses.play_loss, r.final_losses.consistency_loss);
    csv << buf;
    if (has_success) csv << "," << r.success_rate;
    for (const std::string& key : detail_keys) {
      const auto it = r.details.find(key);
      csv << ",";
      if (it != r.details.end()) csv << it->second;
    }
    csv << "\n";
  }
  return csv.str();
}

/// How long each run trained: wall-clock facts, kept out of results.csv.
std::string TimingCsv(const std::vector<RunResult>& runs) {
  std::ostringstream csv;
  csv << "condition,demos,run,train_seconds\n";
  char buf[256];
  for (const RunResult& r : runs) {
    std::snprintf(buf, sizeof(buf), "%s,%d,%d,%.3f\n", r.condition.c_str(), r.demos, r.run,
                  r.train_seconds);
    csv << buf;
  }
  return csv.str();
}

json SummaryBlock(const ConditionSummary& s, const ExperimentResult& result) {
  json block = {{"label", s.label},
                {"mean", s.mean},
                {"sem", s.sem},
                {"n", s.n},
                {"diverged", s.diverged},
                {"train_steps", s.train_steps},
                {"mean_attempts", s.mean_attempts},
                {"mean_train_seconds", s.mean_train_seconds}};
  // The metric also under its own short name ("distance", "action_mse"), as a reader expects.
  if (!result.metric_key.empty()) block[result.metric_key] = s.mean;
  if (!s.details.empty()) block["details"] = s.details;
  if (result.has_success) {
    block["success_rate"] = s.success_rate;
    block["success_sem"] = s.success_sem;
  }
  return block;
}

// The paper's teaching-time accounting (Sec. V): demonstrations, beacon placements and play data
// cost the teacher time; RECON adds the last two. Demonstration and play time are what the
// simulated teleop took (steps x control period); the beacon's attach-and-remove time is the
// paper's measured 2.3 s each, as a simulator cannot measure a human's hands.
constexpr double kBeaconPlacementSeconds = 2.3;
constexpr int kPlacementsPerBeacon = 2;  // attach before teaching, remove after

json TeachingTime(const ExperimentConfig& config, const ExperimentResult& result) {
  // A demonstration lasts as long as the recordings did (they stop when the teacher is done).
  double samples = 0, recorded_demos = 0;
  for (const RunResult& r : result.runs) {
    samples += static_cast<double>(r.demo_samples);
    recorded_demos += r.demos;
  }
  const double demo_seconds =
      (recorded_demos > 0 ? samples / recorded_demos : result.episode_length) * result.step_seconds;
  const double play_seconds_per_demo = result.play_per_scenario * result.step_seconds;
  json totals = json::object();
  for (int demos : config.demos) {
    for (const Condition& c : config.conditions) {
      const bool beacon = c.method == learn::Method::kRecon;
      const double beacons = beacon ? kPlacementsPerBeacon * kBeaconPlacementSeconds : 0.0;
      const double play = c.use_play ? demos * play_seconds_per_demo : 0.0;
      totals[std::to_string(demos)][c.name] = {{"demonstrations_s", demos * demo_seconds},
                                               {"beacon_placements_s", beacons},
                                               {"play_s", play},
                                               {"total_s", demos * demo_seconds + beacons + play}};
    }
  }
  return {{"seconds_per_demonstration", demo_seconds},
          {"seconds_per_beacon_placement", kBeaconPlacementSeconds},
          {"beacon_placements_per_session", kPlacementsPerBeacon},
          {"play_seconds_per_demonstration", play_seconds_per_demo},
          {"by_demos", totals},
          {"paper",
           {{"seconds_per_demonstration", 16.6},
            {"seconds_per_beacon_placement", 2.3},
            {"four_demos_baseline_s", 66.4},
            {"four_demos_recon_play_s", 75.0}}},
          {"note",
           "demonstration and play seconds are the simulated teleop's (recorded samples x control "
           "period, averaged over every run's demonstrations); "
           "beacon placement uses the paper's measured 2.3 s"}};
}

json SummaryJson(const ExperimentConfig& config, const ExperimentResult& result,
                 const std::vector<ConditionSummary>& summaries) {
  json by_demos = json::object();
  for (const ConditionSummary& s : summaries) {
    by_demos[std::to_string(s.demos)]["conditions"][s.condition] = SummaryBlock(s, result);
  }
  json conditions = by_demos[std::to_string(config.demos.front())]["conditions"];
  json train = {
      {"loss", learn::ToString(config.train.loss)},
      {"backend", learn::ToString(config.train.backend)},
      {"learning_rate", config.train.learning_rate},
      {"lr_schedule", learn::ToString(config.train.lr_schedule)},
      {"batch_size", config.train.batch_size},
      {"steps", config.train.steps},
      {"baseline_steps", config.baseline_steps},
      {"policy_ensemble", config.policy_ensemble},
      {"weights",
       {config.train.action_weight, config.train.beacon_weight, config.train.play_weight}},
      {"restart_rule", config.train.restart_rule},
      {"standardize_targets", config.train.standardize_targets},
      {"standardize_inputs", config.train.standardize_inputs},
      {"random_shift_px", config.train.random_shift_px},
      {"random_erase_px", config.train.random_erase_px},
      {"feature_noise", config.train.feature_noise},
      {"beacon_filter_samples", config.train.beacon_filter_samples},
      {"play_consistency", config.train.play_consistency},
      {"nll_min_std", config.train.nll_min_std},
      {"action_min_std", config.train.action_min_std},
      {"weight_decay", config.train.weight_decay},
      {"gate_margin", config.train.gate_margin},
      {"gate_target", learn::ToString(config.train.gate_target)},
      {"play_per_scenario", config.play_per_scenario}};
  json network = {{"feature_dim", config.network.feature_dim},
                  {"policy_hidden", config.network.policy_hidden},
                  {"spatial_softmax", config.network.spatial_softmax},
                  {"action_chunk", config.network.action_chunk},
                  // [] = every action (ACT's ensemble).
                  {"ensembled_actions", config.network.ensembled_actions},
                  {"feature_gate_hidden", config.network.feature_gate_hidden}};
  json beacon_noise = json::object();
  for (const Condition& c : config.conditions) beacon_noise[c.name] = c.noise_sigma;
  // What the demonstrations were recorded under (docs/cell.md).
  json protocol = {{"layout", config.cell.layout},
                   {"demo_noise", config.demo_noise},
                   {"demo_noise_seeds", "DemoNoiseSeed(seed, run)"},
                   {"beacon_noise", beacon_noise}};
  json seeds = {{"seed", config.seed},
                {"demo_scenarios", "DemoScenarioSeed(seed, run, index)"},
                {"training", "TrainSeed(seed, run)"},
                {"test_scenarios", "TestScenarioSeed(seed, index)"}};
  return {{"experiment", config.world},
          {"metric",
           {{"name", result.metric_name},
            {"key", result.metric_key},
            {"higher_is_better", result.higher_is_better},
            {"expert", result.expert_metric}}},
          {"conditions", conditions},
          {"by_demos", by_demos},
          {"demos", config.demos},
          {"runs", config.runs},
          {"tests", config.tests},
          {"seeds", seeds},
          {"authors_compat", config.authors_compat},
          {"jobs", config.jobs},
          // Training is chaotic under rounding: the same seeds give other models on another CPU
          // or kernel table (docs/results.md), so the numbers say where they were measured.
          {"machine", {{"cpu", CpuModelName()}, {"kernels", learn::KernelsInUse()}}},
          {"train", train},
          {"network", network},
          {"protocol", protocol},
          {"wall_seconds", result.wall_seconds}};
}

std::string Subtitle(const ExperimentConfig& config, const ExperimentResult& result, int demos) {
  std::ostringstream s;
  s << config.runs << " runs per bar (mean \xC2\xB1 standard error), " << demos << " demos, "
    << config.tests << " test scenarios, seed " << config.seed << ", "
    << learn::ToString(config.train.loss) << " loss; "
    << (result.higher_is_better ? "higher" : "lower") << " is better";
  return s.str();
}

// The metric's name without its parenthetical (which says higher or lower is better; the
// subtitle says that), so it fits along the y axis.
std::string AxisLabel(const std::string& metric_name) {
  return metric_name.substr(0, metric_name.find(" ("));
}

std::string WorldTitle(const ExperimentConfig& config) {
  if (config.world == "dynamic2d") return "Dynamic 2D";
  if (config.world == "static2d") return "Static 2D";
  if (config.world == "bintransfer") return "Bin transfer";
  if (config.world == "tabletop") return "Tabletop";
  if (config.world == "tabletop-state") return "Tabletop, true object positions (diagnostic)";
  return config.world;
}

}  // namespace

std::vector<ConditionSummary> Summarize(const ExperimentConfig& config,
                                        const ExperimentResult& result) {
  std::vector<ConditionSummary> out;
  for (int demos : config.demos) {
    for (const Condition& c : config.conditions) {
      ConditionSummary s;
      s.condition = c.name;
      s.label = c.label;
      s.demos = demos;
      s.train_steps = TrainSteps(config, c);
      std::vector<double> metrics, success;
      double attempts = 0, seconds = 0;
      int runs = 0;
      std::map<std::string, int> detail_runs;  // a detail a run lacks is not a zero
      for (const RunResult& r : result.runs) {
        if (r.condition != c.name || r.demos != demos) continue;
        ++runs;
        attempts += r.attempts;
        seconds += r.train_seconds;
        if (std::isfinite(r.metric)) {
          metrics.push_back(r.metric);
          success.push_back(r.success_rate);
          for (const auto& [key, value] : r.details) {
            s.details[key] += value;
            ++detail_runs[key];
          }
        } else {
          ++s.diverged;
        }
      }
      s.mean = Mean(metrics);
      s.sem = StandardError(metrics);
      s.n = static_cast<int>(metrics.size());
      for (auto& [key, value] : s.details) value /= static_cast<double>(detail_runs[key]);
      s.success_rate = Mean(success);
      s.success_sem = StandardError(success);
      s.mean_attempts = runs > 0 ? attempts / runs : 0;
      s.mean_train_seconds = runs > 0 ? seconds / runs : 0;
      out.push_back(s);
    }
  }
  return out;
}

std::vector<std::string> WriteExperimentOutputs(const ExperimentConfig& config,
                                                const ExperimentResult& result,
                                                const std::string& dir) {
  EnsureWritableDirectory(dir);
  const std::vector<ConditionSummary> summaries = Summarize(config, result);
  const fs::path root(dir);
  std::vector<std::string> written;

  // The paper-style bar figure, for the first demonstration count.
  report::BarChart bars;
  bars.title = WorldTitle(config) +
               (config.world == "dynamic2d" ? ": beacon placements" : ": beacons and play data");
  bars.subtitle = Subtitle(config, result, config.demos.front());
  bars.y_label = AxisLabel(result.metric_name);
  for (const ConditionSummary& s : summaries) {
    if (s.demos != config.demos.front()) continue;
    bars.labels.push_back(s.label);
    bars.values.push_back(s.mean);
    bars.errors.push_back(s.sem);
  }
  char expert[64];
  std::snprintf(expert, sizeof(expert), "expert %.3f", result.expert_metric);
  bars.references.push_back({result.expert_metric, expert});
  const std::string figure = (root / (config.world + ".png")).string();
  report::WriteChart(bars, figure);
  report::WriteChart(bars, (root / (config.world + ".svg")).string());
  written.push_back(figure);

  if (result.has_success) {
    // Success is what a lab reads first for a robot task: one group of bars per demo count.
    report::BarChart success;
    success.title = WorldTitle(config) + ": success rate with the beacons removed";
    success.subtitle = std::to_string(config.runs) +
                       " runs per bar (mean \xC2\xB1 standard "
                       "error), " +
                       std::to_string(config.tests) + " test scenarios, seed " +
                       std::to_string(config.seed);
    success.y_label = "success rate";
    success.y_min = 0.0;
    success.y_max = 1.0;
    for (const ConditionSummary& s : summaries) {
      success.labels.push_back(
          config.demos.size() > 1 ? s.label + ", " + std::to_string(s.demos) + " demos" : s.label);
      success.values.push_back(s.success_rate);
      success.errors.push_back(s.success_sem);
    }
    char expert_success[64];
    std::snprintf(expert_success, sizeof(expert_success), "expert %.2f",
                  result.expert_success_rate);
    success.references.push_back({result.expert_success_rate, expert_success});
    const std::string path = (root / "success.png").string();
    report::WriteChart(success, path);
    written.push_back(path);
  }

  if (config.demos.size() > 1) {
    report::LineChart curve;
    curve.title = WorldTitle(config) + ": data efficiency";
    curve.subtitle = std::to_string(config.runs) + " runs per point (mean \xC2\xB1 standard error)";
    curve.x_label = "demonstrations";
    curve.y_label = AxisLabel(result.metric_name);
    for (size_t c = 0; c < config.conditions.size(); ++c) {
      report::LineChart::Series series;
      series.name = config.conditions[c].label;
      for (const ConditionSummary& s : summaries) {
        if (s.condition != config.conditions[c].name) continue;
        series.x.push_back(s.demos);
        series.y.push_back(s.mean);
        series.errors.push_back(s.sem);
      }
      curve.series.push_back(series);
    }
    curve.references.push_back({result.expert_metric, expert});
    const std::string path = (root / "data_efficiency.png").string();
    report::WriteChart(curve, path);
    written.push_back(path);
  }

  report::LineChart losses;
  losses.title = WorldTitle(config) + ": action loss while training (run 0)";
  losses.subtitle = "window means, " + learn::ToString(config.train.loss) + " loss, " +
                    std::to_string(config.demos.front()) + " demos";
  losses.x_label = "training step";
  losses.y_label = "action loss";
  losses.log_y = config.train.loss == learn::LossKind::kMseSample;
  for (size_t c = 0; c < config.conditions.size(); ++c) {
    const LossCurve& lc = result.loss_curves[c];  // first demo count comes first
    if (lc.step.empty()) continue;
    report::LineChart::Series series;
    series.name = config.conditions[c].label;
    series.x = lc.step;
    series.y = lc.action_loss;
    series.markers = false;
    losses.series.push_back(series);
  }
  if (!losses.series.empty()) {
    const std::string path = (root / "losses.png").string();
    report::WriteChart(losses, path);
    written.push_back(path);
  }

  const std::string csv = (root / "results.csv").string();
  WriteFileAtomically(csv, ResultsCsv(result.runs, result.has_success));
  written.push_back(csv);
  const std::string timing = (root / "timing.csv").string();
  WriteFileAtomically(timing, TimingCsv(result.runs));
  written.push_back(timing);
  std::error_code ignored;  // the runs so far are in results.csv now
  fs::remove(root / kRunsSoFarFile, ignored);
  // summary.json last: its presence marks a complete result folder.
  const std::string summary = (root / "summary.json").string();
  json summary_json = SummaryJson(config, result, summaries);
  if (result.step_seconds > 0) summary_json["teaching_time"] = TeachingTime(config, result);
  if (result.has_success)
    summary_json["metric"]["expert_success_rate"] = result.expert_success_rate;
  WriteFileAtomically(summary, summary_json.dump(2) + "\n");
  written.push_back(summary);
  return written;
}

void WriteRunsSoFar(std::vector<RunResult> finished, const std::string& dir) {
  std::sort(finished.begin(), finished.end(), [](const RunResult& a, const RunResult& b) {
    return std::tie(a.demos, a.condition, a.run) < std::tie(b.demos, b.condition, b.run);
  });
  const bool has_success = !finished.empty() && finished.front().has_success;
  WriteFileAtomically((fs::path(dir) / kRunsSoFarFile).string(), ResultsCsv(finished, has_success));
}

}  // namespace recon::experiments
