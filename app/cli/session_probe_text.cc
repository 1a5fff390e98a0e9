// What a probe found, for people: the sentence saying how it was made, the verdicts, the table
// and the heat maps (`recon eval --probe`, the studio's Rollouts step and the report).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/cli/session_probe.h"

namespace recon::cli {

namespace {

/// A read-out R^2 at or above this says the features encode the object.
constexpr double kEncodes = 0.5;

std::string Percent(double share) {
  char text[16];
  std::snprintf(text, sizeof(text), "%.0f %%", 100.0 * share);
  return text;
}

/// The heat map's frame: the grid over the table from behind the robot, with every object's
/// place marked.
report::HeatMap GridMap(const store::ProbeSummary& summary, const std::string& object) {
  report::HeatMap map;
  map.x_min = summary.bounds[0];
  map.x_max = summary.bounds[1];
  map.y_min = summary.bounds[2];
  map.y_max = summary.bounds[3];
  map.nx = summary.nx;
  map.ny = summary.ny;
  map.robot_view = true;
  for (const auto& [name, xy] : summary.layout) {
    map.markers.push_back({xy[0], xy[1], name == object ? name + " (home)" : name});
  }
  return map;
}

}  // namespace

std::string ProbeNote(const store::ProbeSummary& summary) {
  char note[512];
  if (summary.readout_scenes == 0) {
    std::snprintf(note, sizeof(note),
                  "Read out on %d recorded frames of %d episodes against the beacons' readings, "
                  "cross-validated over the episodes (each quarter held out whole in turn; the "
                  "networks were trained on these frames, the read-out never on the episode it "
                  "predicts). The objects were not moved: that needs the simulated cell.",
                  summary.readout_frames, summary.readout_episodes);
    return note;
  }
  std::snprintf(note, sizeof(note),
                "Objects moved one at a time over a %d x %d grid in test scene %llu; read-out "
                "fitted and scored on %d other test scenes (seeds from %llu, one in four held "
                "out).",
                summary.nx, summary.ny, static_cast<unsigned long long>(summary.scene_seed),
                summary.readout_scenes, static_cast<unsigned long long>(summary.readout_seed));
  std::string text = note;
  if (HasOutcomes(summary)) {
    text +=
        " Whole rollouts from each place that leaves the task doable (the arm reaches "
        "every grasp and release point).";
  }
  return text;
}

bool HasOutcomes(const store::ProbeSummary& summary) {
  for (const auto& [method, probed] : summary.methods) {
    for (const auto& [object, o] : probed.objects) {
      if (o.success_rate) return true;
    }
  }
  return false;
}

report::HeatMap ProbeHeatMap(const store::ProbeSummary& summary, const std::string& method,
                             const std::string& object) {
  const store::ProbedMethod& probed = summary.methods.at(method);
  const store::ProbedObject& o = probed.objects.at(object);
  double top = 0;  // the object's largest change over every method: one colour scale
  for (const auto& [other, p] : summary.methods) {
    const auto found = p.objects.find(object);
    if (found == p.objects.end()) continue;
    for (double v : found->second.action_change) {
      if (std::isfinite(v)) top = std::max(top, v);
    }
  }
  report::HeatMap map = GridMap(summary, object);
  map.title = probed.label + ": the " + object + " moved";
  char subtitle[160];
  std::snprintf(subtitle, sizeof(subtitle),
                "action change %.3g per 10 cm of %s motion; scene seed %llu, everything else held",
                o.action_change_per_10cm.value_or(NAN), object.c_str(),
                static_cast<unsigned long long>(summary.scene_seed));
  map.subtitle = subtitle;
  map.value_label = "action change";
  map.values = o.action_change;
  map.scale_max = top;
  return map;
}

report::HeatMap ProbeOutcomeMap(const store::ProbeSummary& summary, const std::string& method,
                                const std::string& object) {
  const store::ProbedMethod& probed = summary.methods.at(method);
  const store::ProbedObject& o = probed.objects.at(object);
  int places = 0;
  for (double v : o.outcome) places += std::isfinite(v) ? 1 : 0;
  report::HeatMap map = GridMap(summary, object);
  map.title = probed.label + ": whole rollouts, the " + object + " moved";
  map.subtitle =
      "succeeded from " + Percent(o.success_rate.value_or(0)) + " of " + std::to_string(places) +
      " places (as the scene was: " + (o.home_succeeded.value_or(false) ? "success" : "failure") +
      ")";
  map.value_label = "succeeded (1) or failed (0)";
  map.values = o.outcome;
  map.scale_max = 1;
  return map;
}

std::vector<std::string> ProbeVerdicts(const store::ProbeSummary& summary) {
  std::vector<std::string> verdicts;
  char line[256];
  for (const auto& [method, probed] : summary.methods) {
    // What the action moves with most, over the objects moved.
    const std::pair<const std::string, store::ProbedObject>* most = nullptr;
    for (const auto& entry : probed.objects) {
      if (!entry.second.action_change_per_10cm) continue;
      if (most == nullptr ||
          *entry.second.action_change_per_10cm > *most->second.action_change_per_10cm) {
        most = &entry;
      }
    }
    if (most != nullptr) {
      std::snprintf(line, sizeof(line), "%s moves most with the %s (%.3g per 10 cm",
                    probed.label.c_str(), most->first.c_str(),
                    *most->second.action_change_per_10cm);
      std::string verdict = line;
      for (const auto& [object, o] : probed.objects) {
        if (object == most->first || !o.action_change_per_10cm) continue;
        std::snprintf(line, sizeof(line), "; the %s %.3g", object.c_str(),
                      *o.action_change_per_10cm);
        verdict += line;
      }
      verdicts.push_back(verdict + ")");
    }
    // Whole rollouts: does it still do the task with each object elsewhere?
    std::string outcome;
    for (const auto& [object, o] : probed.objects) {
      if (!o.success_rate) continue;
      outcome += (outcome.empty() ? probed.label + " succeeds from " : ", ") +
                 Percent(*o.success_rate) + " of the " + object + "'s places";
    }
    if (!outcome.empty()) verdicts.push_back(outcome);
    // What the features encode: "RECON's features encode the plate (R^2 0.97), not the bowl".
    std::string encoded, not_encoded;
    for (const auto& [object, o] : probed.objects) {
      if (!o.readout_r2) continue;
      std::snprintf(line, sizeof(line), "the %s (R\u00b2 %.2f)", object.c_str(), *o.readout_r2);
      std::string& list = *o.readout_r2 >= kEncodes ? encoded : not_encoded;
      list += (list.empty() ? "" : ", ") + std::string(line);
    }
    if (!encoded.empty() || !not_encoded.empty()) {
      verdicts.push_back(probed.label + "'s features encode " +
                         (encoded.empty() ? "none of the objects read out" : encoded) +
                         (not_encoded.empty() ? "" : ", not " + not_encoded));
    }
  }
  return verdicts;
}

std::string ProbeSummaryText(const store::ProbeSummary& summary) {
  const bool outcomes = HasOutcomes(summary);
  std::string text;
  char line[256];
  std::snprintf(line, sizeof(line), "%-18s %-8s %16s %16s %12s%s\n", "method", "object",
                "action /10 cm", "feature /10 cm", "read-out R2", outcomes ? "    succeeded" : "");
  text += line;
  const auto number = [](const std::optional<double>& v, const char* format) {
    char cell[32] = "-";
    if (v) std::snprintf(cell, sizeof(cell), format, *v);
    return std::string(cell);
  };
  for (const auto& [method, probed] : summary.methods) {
    for (const auto& [object, o] : probed.objects) {
      std::snprintf(line, sizeof(line), "%-18s %-8s %16s %16s %12s", probed.label.c_str(),
                    object.c_str(), number(o.action_change_per_10cm, "%.4g").c_str(),
                    number(o.feature_change_per_10cm, "%.4g").c_str(),
                    number(o.readout_r2, "%.2f").c_str());
      text += line;
      if (outcomes) {
        std::snprintf(line, sizeof(line), " %12s",
                      o.success_rate ? Percent(*o.success_rate).c_str() : "-");
        text += line;
      }
      text += "\n";
    }
  }
  for (const std::string& verdict : ProbeVerdicts(summary)) text += verdict + "\n";
  text += ProbeNote(summary) + "\n";
  return text;
}

}  // namespace recon::cli
