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
/// Optionally the inputs too (TrainConfig::standardize_inputs): the robot state x and a vector
/// observation y, standardised the same way before the networks see them, in training and when
/// acting. Empty input vectors mean "inputs as recorded".
struct TargetScaling {
  std::vector<float> u_offset, u_scale;  ///< u_dim each
  std::vector<float> b_offset, b_scale;  ///< b_dim each
  std::vector<float> x_offset, x_scale;  ///< x_dim each, or empty
  std::vector<float> y_offset, y_scale;  ///< a vector y's size each, or empty (images: always)

  bool ScalesInputs() const { return !x_offset.empty(); }
  /// Adds input standardisation fitted on `data` (x over demonstrations and play; a vector y
  /// too). Call before Apply.
  void FitInputs(const TrainingData& data);
  /// Standardises one observation's x (and vector y) in place, as the networks saw them.
  void ApplyToInputs(float* x, float* y) const;

  /// Offsets 0 and scales 1: the authors' recipe (raw targets).
  static TargetScaling Identity(const DataSpec& spec);
  /// Mean and standard deviation of u over the demonstrations, and of b over demonstrations and
  /// play together. A dimension that never varies keeps scale 1.
  static TargetScaling Fit(const TrainingData& data);

  /// Rewrites the targets stored in `data` in standardised units.
  void Apply(TrainingData& data) const;
  /// Maps `rows` rows of head means (row stride `stride`) back to the user's units, in place:
  /// `width` values per row (a chunk of actions; -1: one action).
  void RestoreActions(float* rows, int count, int stride, int width = -1) const;
  void RestoreBeacons(float* rows, int count, int stride) const;

  /// Offsets then scales of u, then of b (then of x and y when inputs are scaled), as one flat
  /// vector (for checkpoints), and back.
  std::vector<float> Flatten() const;
  static TargetScaling Unflatten(const DataSpec& spec, const std::vector<float>& flat);

  bool operator==(const TargetScaling& other) const = default;
};

}  // namespace recon::learn
