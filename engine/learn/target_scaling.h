#pragma once

// Per-dimension standardisation of the regression targets (actions u and beacon readings b).
//
// Why: with the paper's Gaussian negative log-likelihood, a head whose targets are large (a
// beacon reports positions up to 10 units away) can lower its loss faster by inflating its
// predicted variance than by fitting its mean, and the mean's gradient, (mean - t) / var, then
// fades: training stalls (docs/results.md measures it on Dynamic 2D). Standardising the targets
// to zero mean and unit spread removes the scale problem for any units a lab records in.

#include <vector>

#include "engine/core/dataset.h"

namespace recon::learn {

struct TrainingData;

/// target_standardised = (target - offset) / scale, per dimension; outputs are mapped back.
struct TargetScaling {
  std::vector<float> u_offset, u_scale;  ///< u_dim each
  std::vector<float> b_offset, b_scale;  ///< b_dim each

  /// Offsets 0 and scales 1: the authors' recipe (raw targets).
  static TargetScaling Identity(const DataSpec& spec);
  /// Mean and standard deviation of u over the demonstrations, and of b over demonstrations and
  /// play together. A dimension that never varies keeps scale 1.
  static TargetScaling Fit(const TrainingData& data);

  /// Rewrites the targets stored in `data` in standardised units.
  void Apply(TrainingData& data) const;
  /// Maps `rows` rows of head means (row stride `stride`) back to the user's units, in place.
  void RestoreActions(float* rows, int count, int stride) const;
  void RestoreBeacons(float* rows, int count, int stride) const;

  /// Offsets then scales of u, then of b, as one flat vector (for checkpoints), and back.
  std::vector<float> Flatten() const;
  static TargetScaling Unflatten(const DataSpec& spec, const std::vector<float>& flat);

  bool operator==(const TargetScaling& other) const = default;
};

}  // namespace recon::learn
