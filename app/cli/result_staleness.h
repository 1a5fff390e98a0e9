#pragma once

// Derived results (a trained model, its rollouts) go out of date when the session changes under
// them: a demonstration recorded, deleted, marked bad or moved to the validation split after
// training, or a model retrained after its rollouts. Nothing is deleted or refused for it; the
// session's info, its report and the studio say which result is out of date and why, so a
// teacher never reads a success rate as that of the data they see.

#include <nlohmann/json.hpp>
#include <string>

#include "engine/store/session.h"

namespace recon::cli {

/// Why `training` (a training/<method>.json record) no longer matches what the session would
/// train on now, e.g. "trained on 6 episodes; since then demo_6 and demo_7 were added"; "" when
/// it matches, or when the record predates `trained_on` (nothing to compare).
std::string TrainingStaleness(const store::Session& session, const nlohmann::json& training);

/// Why `rollouts` (a rollouts/<method>.json record) no longer describe the method's model: the
/// model was retrained after them (its training record has another model_id), or it is missing,
/// or the model they rolled out is itself out of date (TrainingStaleness). `training` is the
/// method's training record, null when there is none.
std::string RolloutStaleness(const store::Session& session, const nlohmann::json& rollouts,
                             const nlohmann::json& training);

}  // namespace recon::cli
