#pragma once

// Smoothing of the beacon readings a learner is trained on (TrainConfig::beacon_filter_samples).
//
// Why: a DWM1001 reports each coordinate with about 7 cm of noise (docs/cell.md), independently
// at every sample. Every camera frame of a demonstration differs (the arm moves), so a feature
// network can learn each frame's noisy reading by heart, and what it learns that way is of no use
// to the policy. The marked objects of a teaching take mostly stand still (the plate while the
// toast is carried; the plate again while the bowl is moved for play data), so the mean of the
// neighbouring readings is a far better target: the readings stay in the session as recorded,
// only the targets are filtered.

#include <cstdint>
#include <vector>

namespace recon::learn {

/// Replaces each row of `b` (one per entry of `group`, `dim` values each) by the mean of the rows
/// within `half_window` rows before and after it that belong to the same group (`group[row]`, rows
/// of a group contiguous, e.g. one demonstration or one play chunk). half_window 0 leaves `b` as it
/// is; one longer than a group averages the whole group.
void SmoothBeaconRows(std::vector<float>& b, int dim, const std::vector<int32_t>& group,
                      int half_window);

/// Group ids for rows laid out as consecutive chunks of the given sizes (empty sizes: each row is
/// its own group, so nothing is averaged across rows whose relation is unknown).
std::vector<int32_t> GroupsOfChunks(int64_t rows, const std::vector<int>& chunk_sizes);

}  // namespace recon::learn
