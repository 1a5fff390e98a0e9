#pragma once

// Derived results (a trained model, its rollouts) go out of date when the session changes under
// them: a demonstration recorded, deleted, marked bad or moved to the validation split after
// training, or a model retrained after its rollouts. Nothing is deleted or refused for it; the
// session's info, its report and the studio say which result is out of date and why, so a
// teacher never reads a success rate as that of the data they see.

#include <map>
#include <optional>
#include <string>

#include "engine/store/real_trials.h"
#include "engine/store/rollout_summary.h"
#include "engine/store/session.h"
#include "engine/store/training_record.h"

namespace recon::cli {

/// The id of the model a checkpoint holds: "fnv1a:" and a digest of the file's bytes, "" when
/// there is no such file. A training record and the rollouts of a model carry the id of the
/// checkpoint they were made with, so a record that outlived its checkpoint (a training killed
/// between saving its model and its record) is found, not only a record that was replaced.
std::string CheckpointModelId(const std::string& path);

/// Why `training` (a method's training record) no longer matches the session: its checkpoint
/// holds another model than the one it describes, or is gone; or the session would now train on
/// other episodes, e.g. "trained on 6 episodes; since then demo_6 and demo_7 were added". ""
/// when it matches, or when the record predates what is compared.
std::string TrainingStaleness(const store::Session& session, const store::TrainingRecord& training);

/// Why `rollouts` (a method's rollout summary) no longer describe the method's model: the
/// checkpoint now holds another model than the one rolled out (retrained), or is gone, or the
/// model they rolled out is itself out of date (TrainingStaleness). `training` is the method's
/// training record, none when there is none. Rollouts from before checkpoint ids are compared
/// with the training record's id as before.
std::string RolloutStaleness(const store::Session& session, const store::RolloutSummary& rollouts,
                             const std::optional<store::TrainingRecord>& training);

/// A result on disk and why it no longer describes the session ("" when it still does).
template <typename Record>
struct CheckedResult {
  Record record;
  std::string out_of_date;
};

/// What training and rollouts have produced in a session, by method, each checked as above.
struct SessionResults {
  std::map<std::string, CheckedResult<store::TrainingRecord>> training;
  std::map<std::string, CheckedResult<store::RolloutSummary>> rollouts;
  /// Trials on a real arm: out of date once the model they ran was retrained.
  std::map<std::string, CheckedResult<store::RealTrialLog>> trials;
};

/// Why a method's trials on a real arm no longer describe its model ("" when they do).
std::string TrialStaleness(const store::Session& session, const store::RealTrialLog& trials);

/// Reads every training record, rollout summary and trial log of the session and checks each.
/// UserError naming the file and field of one that cannot be read.
SessionResults ReadSessionResults(const store::Session& session);

}  // namespace recon::cli
