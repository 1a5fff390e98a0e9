#include "engine/store/training_record.h"

#include <filesystem>

#include "engine/store/json_fields.h"

namespace recon::store {

namespace {

using json = nlohmann::json;

json LossesToJson(const TrainingLosses& losses) {
  return {{"action_loss", losses.action_loss},
          {"beacon_loss", losses.beacon_loss},
          {"play_loss", losses.play_loss},
          {"consistency_loss", losses.consistency_loss},
          {"total_loss", losses.total_loss}};
}

TrainingLosses LossesFromJson(const FieldReader& reader) {
  TrainingLosses losses;
  losses.action_loss = reader.OptionalNumberOrNan("action_loss", 0.0);
  losses.beacon_loss = reader.OptionalNumberOrNan("beacon_loss", 0.0);
  losses.play_loss = reader.OptionalNumberOrNan("play_loss", 0.0);
  losses.consistency_loss = reader.OptionalNumberOrNan("consistency_loss", 0.0);
  losses.total_loss = reader.OptionalNumberOrNan("total_loss", 0.0);
  return losses;
}

json HistoryToJson(const TrainingHistory& history) {
  return {{"step", history.step},
          {"action_loss", history.action_loss},
          {"beacon_loss", history.beacon_loss},
          {"play_loss", history.play_loss},
          {"consistency_loss", history.consistency_loss},
          {"total_loss", history.total_loss}};
}

TrainingHistory HistoryFromJson(const FieldReader& reader) {
  TrainingHistory history;
  history.step = reader.OptionalIntegers("step");
  history.action_loss = reader.OptionalNumbers("action_loss");
  history.beacon_loss = reader.OptionalNumbers("beacon_loss");
  history.play_loss = reader.OptionalNumbers("play_loss");
  history.consistency_loss = reader.OptionalNumbers("consistency_loss");
  history.total_loss = reader.OptionalNumbers("total_loss");
  return history;
}

}  // namespace

void TrainingHistory::Append(int64_t window_step, const TrainingLosses& losses) {
  step.push_back(window_step);
  action_loss.push_back(losses.action_loss);
  beacon_loss.push_back(losses.beacon_loss);
  play_loss.push_back(losses.play_loss);
  consistency_loss.push_back(losses.consistency_loss);
  total_loss.push_back(losses.total_loss);
}

json TrainingRecordToJson(const TrainingRecord& r) {
  json record = {{"method", r.method},
                 {"label", r.label},
                 {"checkpoint", r.checkpoint},
                 {"steps", r.steps},
                 {"attempts", r.attempts},
                 {"seconds", r.seconds},
                 {"seed", r.seed},
                 {"loss", r.loss},
                 {"batch", r.batch},
                 {"learning_rate", r.learning_rate},
                 {"feature_dim", r.feature_dim},
                 {"play_consistency", r.play_consistency},
                 {"nll_min_std", r.nll_min_std},
                 {"action_min_std", r.action_min_std},
                 {"train_demos", r.train_demos},
                 {"train_samples", r.train_samples},
                 {"play_samples", r.play_samples},
                 {"valid_demos", r.valid_demos},
                 {"final", LossesToJson(r.final_losses)},
                 {"train_action_mse", r.train_action_mse},
                 {"valid_action_mse", r.valid_action_mse ? json(*r.valid_action_mse) : json()},
                 {"history", HistoryToJson(r.history)}};
  if (r.trained_on) {
    record["trained_on"] = {{"episodes", r.trained_on->episodes},
                            {"include_bad", r.trained_on->include_bad},
                            {"use_play", r.trained_on->use_play}};
  }
  if (r.model_id) record["model_id"] = *r.model_id;
  // Only where known: a record written before it was kept reads and writes back as it was.
  if (r.action_chunk > 0) record["action_chunk"] = r.action_chunk;
  return record;
}

TrainingRecord TrainingRecordFromJson(const json& value, const std::string& source,
                                      const std::string& method) {
  const FieldReader top(value, source, "");
  TrainingRecord r;
  r.method = top.OptionalString("method", method);
  r.label = top.OptionalString("label", r.method);
  r.checkpoint = top.OptionalString("checkpoint", "");
  r.model_id = top.OptionalNullableString("model_id");
  if (top.Has("trained_on")) {
    const FieldReader on = top.Object("trained_on");
    r.trained_on = TrainedOn{on.OptionalStrings("episodes"), on.Boolean("include_bad", false),
                             on.Boolean("use_play", false)};
  }
  r.steps = static_cast<int>(top.OptionalInteger("steps", 0));
  r.attempts = static_cast<int>(top.OptionalInteger("attempts", 0));
  r.seconds = top.OptionalNumberOrNan("seconds", 0.0);
  r.seed = top.OptionalUnsigned("seed", 0);
  r.loss = top.OptionalString("loss", "");
  r.batch = static_cast<int>(top.OptionalInteger("batch", 0));
  r.learning_rate = top.OptionalNumberOrNan("learning_rate", 0.0);
  r.feature_dim = static_cast<int>(top.OptionalInteger("feature_dim", 0));
  r.action_chunk = static_cast<int>(top.OptionalInteger("action_chunk", 0));
  r.play_consistency = top.OptionalNumberOrNan("play_consistency", 0.0);
  r.nll_min_std = top.OptionalNumberOrNan("nll_min_std", 0.0);
  r.action_min_std = top.OptionalNumbers("action_min_std");
  r.train_demos = static_cast<int>(top.OptionalInteger("train_demos", 0));
  r.train_samples = top.OptionalInteger("train_samples", 0);
  r.play_samples = static_cast<int>(top.OptionalInteger("play_samples", 0));
  r.valid_demos = static_cast<int>(top.OptionalInteger("valid_demos", 0));
  if (top.Has("final")) r.final_losses = LossesFromJson(top.Object("final"));
  r.train_action_mse = top.OptionalNumberOrNan("train_action_mse", std::nan(""));
  if (top.Has("valid_action_mse") && !top.object().at("valid_action_mse").is_null()) {
    r.valid_action_mse = top.Number("valid_action_mse");
  }
  if (top.Has("history")) r.history = HistoryFromJson(top.Object("history"));
  return r;
}

void WriteTrainingRecord(const std::string& path, const TrainingRecord& record) {
  WriteJsonFile(path, TrainingRecordToJson(record));
}

std::optional<TrainingRecord> ReadTrainingRecord(const Session& session,
                                                 const std::string& method) {
  return ReadRecordFile(session.TrainingRecordPath(method), method, &TrainingRecordFromJson);
}

std::map<std::string, TrainingRecord> ReadTrainingRecords(const Session& session) {
  return ReadRecordsIn((std::filesystem::path(session.dir()) / Session::kTrainingFolder).string(),
                       &TrainingRecordFromJson);
}

}  // namespace recon::store
