#pragma once

// probe/probe.json (Session::ProbeSummaryPath): what the distractor probe and the feature
// read-out found of a session's trained methods (engine/probe), for `recon eval --probe`, the
// studio's Rollouts step and the report.

#include <array>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/store/session.h"

namespace recon::store {

/// One object moved by the probe, for one method.
struct ProbedObject {
  /// |a(moved) - a(home)| and |phi(moved) - phi(home)| per 10 cm of the object's motion; none
  /// when the objects were not moved (a real cell's session: only its recorded frames are read
  /// out).
  std::optional<double> action_change_per_10cm, feature_change_per_10cm;
  /// R^2 of the linear read-out of the object's table position (or, on recorded frames, its
  /// beacon's reading) from phi on held-out scenes; none when the object stands still over
  /// them (nothing to read out).
  std::optional<double> readout_r2;
  /// With whole rollouts (`--outcome`): the share of grid places from which the rollout with
  /// the object there succeeded, and per cell 1 (succeeded), 0 (failed) or NaN (not rolled out:
  /// the object would overlap another, or the task cannot be done there).
  std::optional<double> success_rate;
  std::vector<double> outcome;
  std::optional<bool> home_succeeded;         ///< the rollout of the scene as it was
  std::optional<std::string> outcome_figure;  ///< the outcome's map, relative to the session
  /// The heat map (action change per grid cell), relative to the session; none if not written.
  std::optional<std::string> figure;
  /// Its values: |a(moved) - a(home)| per grid cell, row-major from y_min, NaN where the object
  /// would have overlapped another.
  std::vector<double> action_change;

  bool operator==(const ProbedObject& other) const = default;
};

/// One trained method's probe.
struct ProbedMethod {
  std::string label;
  std::optional<std::string> model_id;  ///< the model probed (TrainingRecord::model_id)
  std::map<std::string, ProbedObject> objects;

  bool operator==(const ProbedMethod& other) const = default;
};

struct ProbeSummary {
  uint64_t scene_seed = 0;  ///< the scene whose objects were moved one at a time
  int nx = 0, ny = 0;       ///< the grid
  std::array<double, 4> bounds = {0, 0, 0, 0};  ///< x_min, x_max, y_min, y_max (metres)
  /// Where the probed scene had each object (table x, y).
  std::map<std::string, std::array<double, 2>> layout;
  int readout_scenes = 0;     ///< test scenes the read-out was fitted and scored on
  uint64_t readout_seed = 0;  ///< their seeds derive from it
  /// A real cell's session is read out on its recorded frames instead (readout_scenes 0): this
  /// many frames of this many episodes, against the beacons' readings.
  int readout_frames = 0, readout_episodes = 0;
  double seconds = 0;
  std::map<std::string, ProbedMethod> methods;  ///< by method ("baseline", "recon")

  bool operator==(const ProbeSummary& other) const = default;
};

/// {"methods": {"<method>": {"<object>": {"action_change_per_10cm": v|null,
/// "feature_change_per_10cm": v|null, "readout_r2": v|null, "figure": path|null,
/// "action_change": [per cell], "success_rate": v|null, "outcome": [per cell],
/// "home_succeeded": b|null, "outcome_figure": path|null}}}, "labels": ..., "layout": ...,
/// "model_ids": ..., "scene_seed": ..., "grid": {...}, "readout": {...}, "seconds": ...}.
nlohmann::json ProbeSummaryToJson(const ProbeSummary& summary);
/// UserError naming `source` and the field for a value of the wrong kind, or a figure path
/// outside the session.
ProbeSummary ProbeSummaryFromJson(const nlohmann::json& value, const std::string& source);
/// Writes the summary atomically.
void WriteProbeSummary(const std::string& path, const ProbeSummary& summary);
/// The session's probe; nullopt when it has none.
std::optional<ProbeSummary> ReadProbeSummary(const Session& session);

}  // namespace recon::store
