#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/store/session.h"

namespace recon::store {

/// How a method's policy did on one test scene.
struct ScenarioResult {
  uint64_t seed = 0;  ///< the scene's
  double metric = 0;
  bool succeeded = false;  ///< only meaningful when the world has a success (has_success)
  std::map<std::string, double> details;  ///< the world's outcome details at the end

  bool operator==(const ScenarioResult& other) const = default;
};

/// rollouts/<method>.json (Session::RolloutSummaryPath): a method's policy rolled out on new
/// scenes of the session's simulated cell with the beacons removed. Every key of the file is a
/// field here; a key missing from an older summary reads as the default below.
struct RolloutSummary {
  std::string method;      ///< "baseline" or "recon" (default: the file's name)
  std::string label;       ///< as its training record's (default: the method)
  std::string checkpoint;  ///< the model, relative to the session (Session::CheckpointRelativePath)
  /// The id of the model rolled out (TrainingRecord::model_id); none (null in the file) when
  /// the rollouts are from before ids, or their model had no training record.
  std::optional<std::string> model_id;
  std::string metric_name = "metric";  ///< the world's, for people
  std::string metric_key;              ///< the world's, short ("distance", "reward")
  bool higher_is_better = false;
  double metric_mean = 0;
  double metric_sem = 0;
  bool has_success = false;
  double success_rate = 0;
  double success_sem = 0;
  std::map<std::string, double> details;  ///< the scenes' details, averaged
  int tests = 0;
  uint64_t seed = 0;  ///< the scenes' seeds derive from it
  double seconds = 0;
  std::vector<ScenarioResult> per_scenario;
  /// The replay of every step, relative to the session (Session::RolloutReplayRelativePath);
  /// none when the world has none or it was not kept.
  std::optional<std::string> replay;

  /// Field by field (a NaN equals nothing, as always).
  bool operator==(const RolloutSummary& other) const = default;
};

/// The summary as its file holds it (nlohmann::json orders keys by name).
nlohmann::json RolloutSummaryToJson(const RolloutSummary& summary);
/// Reads a summary; `method` is what it is of when it does not say. UserError naming `source`
/// and the field for a value of the wrong kind.
RolloutSummary RolloutSummaryFromJson(const nlohmann::json& value, const std::string& source,
                                      const std::string& method);

/// Writes the summary to `path` atomically, in the layout every version has written.
void WriteRolloutSummary(const std::string& path, const RolloutSummary& summary);
/// The method's rollout summary, nullopt when it has none. UserError naming the file (and the
/// field) when it cannot be read.
std::optional<RolloutSummary> ReadRolloutSummary(const Session& session, const std::string& method);
/// Every rollout summary of the session, by method.
std::map<std::string, RolloutSummary> ReadRolloutSummaries(const Session& session);

}  // namespace recon::store
