#include "app/cli/session_summary.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "engine/calib/calibration.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string Format(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

/// Results by method as their files hold them, each with why it is out of date (null if not).
template <typename Record>
json ResultsJson(const std::map<std::string, CheckedResult<Record>>& results,
                 json (*to_json)(const Record&)) {
  json all = json::object();
  for (const auto& [method, result] : results) {
    json item = to_json(result.record);
    item["out_of_date"] = result.out_of_date.empty() ? json(nullptr) : json(result.out_of_date);
    all[method] = item;
  }
  return all;
}

}  // namespace

json TeachingLedgerJson(const store::Session& session) {
  const store::SessionManifest& m = session.manifest();
  const double demos = session.DemoSeconds(false);
  const double play = session.PlaySeconds();
  const double placements = static_cast<double>(m.beacons.size()) * m.placements_per_beacon *
                            m.seconds_per_beacon_placement;
  int usable = 0;
  for (const store::EpisodeEntry& e : session.demos()) usable += !e.flags.bad && e.problem.empty();
  const bool timed = m.step_seconds > 0;
  const double unkept = m.discarded_seconds + m.countdown_seconds;
  return {{"timed", timed},
          {"discarded_takes", m.discarded_takes},
          {"discarded_s", m.discarded_seconds},
          {"countdowns_s", m.countdown_seconds},
          // Everything the teacher spent: kept and unkept takes, countdowns, play, beacons.
          {"teacher_total_s", demos + play + placements + unkept},
          {"demonstrations", usable},
          {"demonstrations_s", demos},
          {"seconds_per_demonstration", usable > 0 ? demos / usable : 0.0},
          {"play_s", play},
          {"beacon_placements_s", placements},
          {"seconds_per_beacon_placement", m.seconds_per_beacon_placement},
          {"placements_per_beacon", m.placements_per_beacon},
          {"baseline_total_s", demos},
          {"recon_total_s", demos + placements},
          {"recon_play_total_s", demos + placements + play},
          {"paper",
           {{"seconds_per_demonstration", 16.6},
            {"four_demos_baseline_s", 66.4},
            {"four_demos_recon_play_s", 75.0}}},
          {"note",
           timed ? "demonstration and play seconds are what the recordings took (samples x "
                   "control period in the simulated cell); beacon placement uses the paper's "
                   "measured 2.3 s, twice per beacon (on and off)"
                 : "this world is abstract (no control period), so its demonstrations and play "
                   "cost no teaching time here; beacon placement uses the paper's measured 2.3 s, "
                   "twice per beacon (on and off)"}};
}

json EpisodesJson(const store::Session& session) {
  json list = json::array();
  for (const auto* entries : {&session.demos(), &session.play_chunks()}) {
    for (const store::EpisodeEntry& e : *entries) {
      json item = {{"name", e.name},
                   {"kind", e.name.rfind("demo_", 0) == 0 ? "demo" : "play"},
                   {"file", e.path}};
      if (!e.problem.empty()) {
        item["problem"] = e.problem;
      } else {
        item.update({{"samples", e.meta.num_samples},
                     {"seed", e.meta.seed},
                     {"teaching_seconds", e.meta.teaching_seconds},
                     {"succeeded", e.meta.succeeded},
                     {"recorded_at", e.meta.recorded_at},
                     {"source", e.meta.source},
                     {"bad", e.flags.bad},
                     {"split", e.flags.split},
                     {"note", e.flags.note}});
      }
      list.push_back(item);
    }
  }
  return list;
}

json SessionInfoJson(const store::Session& session, const SessionResults& results) {
  const store::SessionManifest& m = session.manifest();
  int usable = 0, bad = 0, train = 0, valid = 0, succeeded = 0;
  int64_t samples = 0;
  json damaged = json::array();
  for (const store::EpisodeEntry& e : session.demos()) {
    if (!e.problem.empty()) {
      damaged.push_back({{"name", e.name}, {"problem", e.problem}});
      continue;
    }
    ++usable;
    samples += e.meta.num_samples;
    bad += e.flags.bad;
    succeeded += e.meta.succeeded;
    if (!e.flags.bad) (e.flags.split == "valid" ? valid : train)++;
  }
  for (const store::EpisodeEntry& e : session.play_chunks()) {
    if (!e.problem.empty()) damaged.push_back({{"name", e.name}, {"problem", e.problem}});
  }
  // The beacons exactly as the manifest stores them.
  const json beacons = json::parse(store::ManifestToJson(m))["beacons"];
  json info = {{"dir", session.dir()},
               {"world", m.world},
               {"cell", m.cell},
               {"placement", m.placement},
               {"created_at", m.created_at},
               {"seed", m.seed},
               {"spec", m.spec.ToString()},
               {"beacons", beacons},
               {"episodes", usable},
               {"demo_samples", samples},
               {"succeeded", succeeded},
               {"bad", bad},
               {"train", train},
               {"valid", valid},
               {"play", session.PlaySamples()},
               {"play_chunks", session.play_chunks().size()},
               {"damaged", damaged},
               {"teaching_time", TeachingLedgerJson(session)},
               {"training", ResultsJson(results.training, &store::TrainingRecordToJson)},
               {"rollouts", ResultsJson(results.rollouts, &store::RolloutSummaryToJson)},
               {"real_trials", ResultsJson(results.trials, &store::RealTrialLogToJson)}};
  info["calibration"] = nullptr;
  if (!m.calibration_file.empty()) {
    const calib::CalibrationReport cal =
        calib::LoadCalibration((fs::path(session.dir()) / m.calibration_file).string());
    info["calibration"] = {{"rmse_m", cal.rmse_m},
                           {"p95_m", cal.p95_m},
                           {"points", cal.points.size()},
                           {"inliers", cal.num_inliers},
                           {"passed", cal.passed}};
  }
  return info;
}

std::string SessionInfoText(const store::Session& session, const json& info,
                            const SessionResults& results) {
  std::ostringstream out;
  const store::SessionManifest& m = session.manifest();
  out << "session " << session.dir() << ": " << m.world << " (" << m.cell << " cell), created "
      << m.created_at << ", seed " << m.seed << "\n";
  out << "  shapes:         " << m.spec.ToString() << "\n";
  out << "  beacons:        ";
  if (m.beacons.empty()) out << "none";
  for (size_t i = 0; i < m.beacons.size(); ++i) {
    const BeaconSpec& b = m.beacons[i];
    out << (i > 0 ? "; " : "") << b.name << " on " << b.object << " (" << b.quantity << ", "
        << b.dim << " values" << (b.unit.empty() ? "" : ", " + b.unit) << ")";
  }
  out << "\n";
  out << "  demonstrations: " << info["episodes"].get<int>() << " committed ("
      << info["demo_samples"].get<int64_t>() << " samples, " << info["succeeded"].get<int>()
      << " done the task), " << info["bad"].get<int>() << " bad, " << info["train"].get<int>()
      << " train / " << info["valid"].get<int>() << " valid\n";
  out << "  play:           " << info["play"].get<int64_t>() << " samples in "
      << info["play_chunks"].get<size_t>() << " chunks\n";
  for (const json& d : info["damaged"]) {
    out << "  DAMAGED:        " << d["name"].get<std::string>() << ": "
        << d["problem"].get<std::string>() << "\n";
  }
  const json& ledger = info["teaching_time"];
  if (!ledger["timed"].get<bool>()) {
    out << "  teaching time:  not timed (an abstract world has no control period); beacon "
           "placements would add "
        << Format("%.1f", ledger["beacon_placements_s"]) << " s\n";
  } else {
    out << "  teaching time:  demonstrations " << Format("%.1f", ledger["demonstrations_s"])
        << " s, play " << Format("%.1f", ledger["play_s"]) << " s, beacon placements "
        << Format("%.1f", ledger["beacon_placements_s"]) << " s; Baseline "
        << Format("%.1f", ledger["baseline_total_s"]) << " s vs RECON (Play) "
        << Format("%.1f", ledger["recon_play_total_s"]) << " s\n";
    // What the kept takes leave out: a person's discarded takes and countdowns.
    const int discarded = ledger["discarded_takes"].get<int>();
    out << "                  everything the teacher spent: "
        << Format("%.1f", ledger["teacher_total_s"]) << " s, with " << discarded
        << (discarded == 1 ? " take" : " takes") << " discarded or recorded over ("
        << Format("%.1f", ledger["discarded_s"]) << " s) and countdowns and waits ("
        << Format("%.1f", ledger["countdowns_s"]) << " s)\n";
  }
  if (info["calibration"].is_null()) {
    out << "  calibration:    none\n";
  } else {
    const json& c = info["calibration"];
    out << "  calibration:    RMSE " << Format("%.4f", c["rmse_m"]) << " m over "
        << c["inliers"].get<int>() << " of " << c["points"].get<size_t>() << " points, "
        << (c["passed"].get<bool>() ? "PASS" : "FAIL") << "\n";
  }
  for (const auto& [method, t] : results.training) {
    out << "  trained:        " << method << ": " << t.record.steps << " steps, final loss "
        << Format("%.4g", t.record.final_losses.total_loss) << "\n";
    if (!t.out_of_date.empty()) {
      out << "  OUT OF DATE:    " << method << ": " << t.out_of_date << "\n";
    }
  }
  for (const auto& [method, r] : results.rollouts) {
    const store::RolloutSummary& summary = r.record;
    out << "  rolled out:     " << method << ": " << summary.metric_name << " "
        << Format("%.4g", summary.metric_mean);
    if (summary.has_success) {
      out << ", success " << Format("%.0f", 100.0 * summary.success_rate) << "%";
    }
    out << " over " << summary.tests << " simulated scenarios\n";
    if (!r.out_of_date.empty()) {
      out << "  OUT OF DATE:    " << method << " rollouts: " << r.out_of_date << "\n";
    }
  }
  for (const auto& [method, t] : results.trials) {
    out << "  real trials:    " << method << ": " << t.record.successes() << " of "
        << t.record.trials.size() << " succeeded on the real arm"
        << (t.record.cell.empty() ? "" : " (" + t.record.cell + ")") << "\n";
    if (!t.out_of_date.empty()) {
      out << "  OUT OF DATE:    " << method << " trials: " << t.out_of_date << "\n";
    }
  }
  return out.str();
}

}  // namespace recon::cli
