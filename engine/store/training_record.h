#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/store/session.h"

namespace recon::store {

/// Which episodes a model learnt from, chosen how (Session::DatasetEpisodeNames), so that the
/// session can tell later whether it would now train on other data.
struct TrainedOn {
  std::vector<std::string> episodes;
  bool include_bad = false;
  bool use_play = false;

  bool operator==(const TrainedOn& other) const = default;
};

/// The loss terms of a training run at one point (learn::StepMetrics's, widened to double).
struct TrainingLosses {
  double action_loss = 0;
  double beacon_loss = 0;
  double play_loss = 0;
  double consistency_loss = 0;
  double total_loss = 0;

  bool operator==(const TrainingLosses& other) const = default;
};

/// A training run's loss curve: every term averaged over windows of steps, one column per term
/// as the record stores them. step[i] is window i's middle step. A column of a record from
/// before its term existed (consistency_loss) is empty.
struct TrainingHistory {
  std::vector<int64_t> step;
  std::vector<double> action_loss;
  std::vector<double> beacon_loss;
  std::vector<double> play_loss;
  std::vector<double> consistency_loss;
  std::vector<double> total_loss;

  void Append(int64_t window_step, const TrainingLosses& losses);
  void Clear() { *this = {}; }
  bool operator==(const TrainingHistory& other) const = default;
};

/// training/<method>.json (Session::TrainingRecordPath): how a method was trained on the session
/// and how it did. Every key of the file is a field here; a key missing from an older record
/// reads as the default below.
struct TrainingRecord {
  std::string method;      ///< "baseline" or "recon" (default: the file's name)
  std::string label;       ///< "Baseline", "RECON", "RECON (Play)" (default: the method)
  std::string checkpoint;  ///< the model, relative to the session (Session::CheckpointRelativePath)
  /// The checkpoint's digest when the record was written ("fnv1a:..."; older records hold a
  /// training's own id), so a record that outlived its model is found. None in records from
  /// before ids.
  std::optional<std::string> model_id;
  /// None in records from before it was kept (such a record is never out of date by its data).
  std::optional<TrainedOn> trained_on;
  int steps = 0;     ///< steps of the final attempt
  int attempts = 0;  ///< tries used (the restart rule)
  double seconds = 0;
  uint64_t seed = 0;
  std::string loss;  ///< "nll" or "mse-sample"
  int batch = 0;
  double learning_rate = 0;
  int feature_dim = 0;
  int action_chunk = 0;  ///< actions predicted at once (0: a record written before it was kept)
  double play_consistency = 0;
  double nll_min_std = 0;
  std::vector<double> action_min_std;
  int train_demos = 0;
  int64_t train_samples = 0;
  int play_samples = 0;  ///< play chunks trained on
  int valid_demos = 0;
  TrainingLosses final_losses;  ///< "final": the last step's losses
  /// The policy's mean action against the demonstrations' (NaN when unknown).
  double train_action_mse = std::nan("");
  std::optional<double> valid_action_mse;  ///< none without validation demonstrations
  TrainingHistory history;

  /// Field by field (a NaN equals nothing, as always).
  bool operator==(const TrainingRecord& other) const = default;
};

/// The record as its file holds it (nlohmann::json orders keys by name).
nlohmann::json TrainingRecordToJson(const TrainingRecord& record);
/// Reads a record; `method` is what it is of when it does not say. UserError naming `source` and
/// the field for a value of the wrong kind.
TrainingRecord TrainingRecordFromJson(const nlohmann::json& value, const std::string& source,
                                      const std::string& method);

/// Writes the record to `path` atomically, in the layout every version has written.
void WriteTrainingRecord(const std::string& path, const TrainingRecord& record);
/// The method's training record, nullopt when it has none. UserError naming the file (and the
/// field) when it cannot be read.
std::optional<TrainingRecord> ReadTrainingRecord(const Session& session, const std::string& method);
/// Every training record of the session, by method.
std::map<std::string, TrainingRecord> ReadTrainingRecords(const Session& session);

}  // namespace recon::store
