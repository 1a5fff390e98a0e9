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
  double action_change_per_10cm = 0;   ///< |a(moved) - a(home)| per 10 cm of the object's motion
  double feature_change_per_10cm = 0;  ///< |phi(moved) - phi(home)| per 10 cm
  /// R^2 of the linear read-out of the object's table position from phi on held-out test
  /// scenes; none when the object stands still over those scenes (nothing to read out).
  std::optional<double> readout_r2;
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
  double seconds = 0;
  std::map<std::string, ProbedMethod> methods;  ///< by method ("baseline", "recon")

  bool operator==(const ProbeSummary& other) const = default;
};

/// {"methods": {"<method>": {"<object>": {"action_change_per_10cm": v,
/// "feature_change_per_10cm": v, "readout_r2": v|null, "figure": path|null, "action_change":
/// [per cell]}}}, "labels": ..., "layout": ...,
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
