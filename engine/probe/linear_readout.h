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
/// hold out one in `fold` spread over the whole run. With `groups` (one per frame), whole
/// groups are held out instead: the frames whose group modulo `fold` is 0 (frames of one
/// recorded episode look alike, so scoring on the episode fitted on would flatter the read-out).
/// UserError for rows of differing sizes, fewer than 2 fitted or held-out frames or no feature.
ReadoutScore FitLinearReadout(const std::vector<std::vector<float>>& features,
                              const std::vector<std::vector<double>>& targets, int fold = 4,
                              double ridge = 1e-3, const std::vector<int>& groups = {});

/// Cross-validated: each group (frame, without `groups`) modulo `folds` is held out in turn and
/// predicted by the read-out fitted on the others; R^2 of every frame's prediction about the
/// mean of all. Steadier than one split when there are few groups (a session's few recorded
/// episodes, each at one place of the object): a single held-out quarter may hold two places
/// only. `ridge` 0 chooses each fold's penalty (1e-3 to 100) by a 3-fold cross-validation
/// within the groups it is fitted on, never on those it predicts. `fitted` is the frames fitted
/// on per fold, `held_out` every frame. UserError as FitLinearReadout, or for a fold with fewer
/// than 2 frames to fit on.
ReadoutScore CrossValidatedReadout(const std::vector<std::vector<float>>& features,
                                   const std::vector<std::vector<double>>& targets,
                                   const std::vector<int>& groups, int folds, double ridge);

}  // namespace recon::probe
