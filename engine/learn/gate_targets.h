#pragma once

// The feature gate's targets by disagreement (GateTarget::kDisagreement): where in the
// demonstrations the robot state alone does not say what the teacher did.

#include <vector>

#include "engine/learn/training_data.h"

namespace recon::learn {

/// Per demonstration row of `data`, how much the teacher's actions there differ from another
/// demonstration's at its nearest robot state: the largest, over the other episodes, of the
/// squared difference per action between this row's action chunk and the best-matching chunk
/// within 5 rows of that episode's nearest row (the same action a few steps off is agreement),
/// in units of the actions' total variance (the sum over action dimensions; two rows drawn at
/// random differ by about 2).
/// `action_scale` is what one stored unit of each action dimension is worth in the user's units
/// (TargetScaling::u_scale when the rows are standardised; empty = as recorded), so that each
/// dimension weighs by its real size. The nearest row is found by Euclidean distance between
/// states standardised per dimension (constant dimensions ignored). 0 for every row when there is
/// a single episode. O(rows^2 x_dim): 0.1 s for 3,000 rows.
std::vector<float> DemonstrationDisagreement(const TrainingData& data,
                                             const std::vector<float>& action_scale = {});

/// 1 where DemonstrationDisagreement exceeds `margin` for at least 2 action_chunk rows in a row
/// of one episode, else 0 (a shorter disagreement is timing, not a choice).
std::vector<float> DisagreementGateTargets(const TrainingData& data,
                                           const std::vector<float>& action_scale, double margin);

}  // namespace recon::learn
