#include "engine/store/rollout_summary.h"

#include <filesystem>

#include "engine/store/json_fields.h"

namespace recon::store {

namespace {
using json = nlohmann::json;
}  // namespace

json RolloutSummaryToJson(const RolloutSummary& s) {
  json per_scenario = json::array();
  for (const ScenarioResult& scenario : s.per_scenario) {
    per_scenario.push_back({{"seed", scenario.seed},
                            {"metric", scenario.metric},
                            {"succeeded", scenario.succeeded},
                            {"details", scenario.details}});
  }
  json summary = {{"method", s.method},
                  {"label", s.label},
                  {"checkpoint", s.checkpoint},
                  {"model_id", s.model_id ? json(*s.model_id) : json()},
                  {"metric_name", s.metric_name},
                  {"metric_key", s.metric_key},
                  {"higher_is_better", s.higher_is_better},
                  {"metric_mean", s.metric_mean},
                  {"metric_sem", s.metric_sem},
                  {"has_success", s.has_success},
                  {"success_rate", s.success_rate},
                  {"success_sem", s.success_sem},
                  {"details", s.details},
                  {"tests", s.tests},
                  {"seed", s.seed},
                  {"seconds", s.seconds},
                  {"per_scenario", per_scenario}};
  if (s.replay) summary["replay"] = *s.replay;
  return summary;
}

RolloutSummary RolloutSummaryFromJson(const json& value, const std::string& source,
                                      const std::string& method) {
  const FieldReader top(value, source, "");
  RolloutSummary s;
  s.method = top.OptionalString("method", method);
  s.label = top.OptionalString("label", s.method);
  s.checkpoint = top.OptionalString("checkpoint", "");
  s.model_id = top.OptionalNullableString("model_id");
  s.metric_name = top.OptionalString("metric_name", s.metric_name);
  s.metric_key = top.OptionalString("metric_key", "");
  s.higher_is_better = top.Boolean("higher_is_better", false);
  s.metric_mean = top.OptionalNumberOrNan("metric_mean", 0.0);
  s.metric_sem = top.OptionalNumberOrNan("metric_sem", 0.0);
  s.has_success = top.Boolean("has_success", false);
  s.success_rate = top.OptionalNumberOrNan("success_rate", 0.0);
  s.success_sem = top.OptionalNumberOrNan("success_sem", 0.0);
  s.details = top.OptionalNumberMap("details");
  s.tests = static_cast<int>(top.OptionalInteger("tests", 0));
  s.seed = top.OptionalUnsigned("seed", 0);
  s.seconds = top.OptionalNumberOrNan("seconds", 0.0);
  if (top.Has("per_scenario")) {
    const json& rows = top.Array("per_scenario");
    for (size_t i = 0; i < rows.size(); ++i) {
      const FieldReader row = top.Element(rows[i], "per_scenario", i);
      s.per_scenario.push_back({row.OptionalUnsigned("seed", 0),
                                row.OptionalNumberOrNan("metric", 0.0),
                                row.Boolean("succeeded", false), row.OptionalNumberMap("details")});
    }
  }
  s.replay = top.OptionalNullableString("replay");
  return s;
}

void WriteRolloutSummary(const std::string& path, const RolloutSummary& summary) {
  WriteJsonFile(path, RolloutSummaryToJson(summary));
}

std::optional<RolloutSummary> ReadRolloutSummary(const Session& session,
                                                 const std::string& method) {
  return ReadRecordFile(session.RolloutSummaryPath(method), method, &RolloutSummaryFromJson);
}

std::map<std::string, RolloutSummary> ReadRolloutSummaries(const Session& session) {
  return ReadRecordsIn((std::filesystem::path(session.dir()) / Session::kRolloutFolder).string(),
                       &RolloutSummaryFromJson);
}

}  // namespace recon::store
