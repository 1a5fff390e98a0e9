#pragma once

// Play consistency (TrainConfig::play_consistency): a RECON term on the play data that asks the
// features of two play samples taken during the same beacon placement to agree.
//
// Why: during play the marked object stands still under its beacon while the teacher moves the
// others (the bowl) around, so whatever changes between two frames of one play chunk is, by the
// teacher's own marking, irrelevant to the task. The paper's beacon term only asks the beacon net
// to read the same reading from both frames: it makes the features it reads blind to the bowl,
// but the other k - d features stay free to follow it, and the policy, which reads all k, then
// meets a bowl position it never saw as an input it never saw (docs/results.md). This term asks
// all k features to agree, in units of their spread over the play batch, so that the feature net
// cannot satisfy it by shrinking. It needs play data (beacon placements), so the Baseline has no
// counterpart, like the beacon term itself.

#include <cstdint>
#include <vector>

#include "engine/core/rng.h"

namespace recon::learn {

/// Added to the spread the loss divides by: keeps it finite when every feature is constant over
/// the batch (a fresh network can start there); small against features that carry anything.
constexpr double kPlayConsistencySpreadFloor = 1e-6;

/// Each play row's chunk as the first row and size of that chunk, for drawing pairs.
struct PlayChunks {
  std::vector<int64_t> first;  ///< [row]: the chunk's first row
  std::vector<int32_t> size;   ///< [row]: the chunk's number of rows

  /// From each row's chunk id (GroupsOfChunks, beacon_filter.h: rows of a chunk contiguous).
  static PlayChunks FromGroups(const std::vector<int32_t>& group);
  /// Another row of `row`'s chunk, uniformly (`row` itself only when the chunk has one row).
  int64_t Partner(int64_t row, Rng& rng) const;
};

/// The consistency loss of a play batch of `batch` rows of `k` features, rows 2p and 2p + 1
/// forming pair p (an odd last row belongs to no pair): the mean over pairs of the squared
/// distance between the pair's features, divided by twice the features' total variance over
/// the batch (sum over the k features). Rows without structure give about 1; features that only
/// differ between chunks give 0. Writes weight * dLoss/dphi into `grad_phi` ([batch][k]; the
/// variance is differentiated too, so scaling the features changes nothing) and returns the
/// unweighted loss. The Torch backend (torch_step.cc) computes the same from autograd.
float PlayConsistencyLoss(const float* phi, int batch, int k, float weight, float* grad_phi);

}  // namespace recon::learn
