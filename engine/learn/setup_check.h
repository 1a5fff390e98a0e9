#pragma once

#include "engine/core/dataset.h"
#include "engine/learn/learner.h"

namespace recon::learn {

/// Throws UserError with a message a user can act on if the data (ValidateDataset) or the
/// settings cannot be trained: RECON without beacons or with k <= d, non-positive steps, batch
/// size or learning rate, negative or non-finite loss weights, no attempts.
void CheckTrainingSetup(const Dataset& data, const NetworkConfig& network,
                        const TrainConfig& train);

}  // namespace recon::learn
