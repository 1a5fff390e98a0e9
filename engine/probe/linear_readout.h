#pragma once

// What the features encode: a linear read-out fitted from phi to a quantity (an object's true
// table position) on some frames and scored on frames it was not fitted on.

#include <vector>

namespace recon::probe {

struct ReadoutScore {
  /// 1 - (squared error on the held-out frames) / (their variance about their mean), pooled
  /// over the target's dimensions: 1 when phi determines the target linearly, about 0 (or
  /// below) when it carries nothing of it.
  double r2 = 0;
  std::vector<double> r2_per_dimension;
  int fitted = 0, held_out = 0;  ///< frames
};

/// Fits target = W phi + c by ridge regression (`ridge` times the features' mean variance on
/// the diagonal, so the penalty does not depend on their units) on every frame whose index
/// modulo `fold` is not 0, and scores the frames whose index is. Frames in time order thus
/// hold out one in `fold` spread over the whole run. UserError for rows of differing sizes,
/// fewer than 2 held-out frames or no feature.
ReadoutScore FitLinearReadout(const std::vector<std::vector<float>>& features,
                              const std::vector<std::vector<double>>& targets, int fold = 4,
                              double ridge = 1e-3);

}  // namespace recon::probe
