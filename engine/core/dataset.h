#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace recon {

/// Shapes of the four signals of a teaching task. y is either a vector ({m}) or a channels-first
/// image ({C, H, W}); x, b and u are vectors.
struct DataSpec {
  int x_dim = 0;                 ///< robot state x (joint angles, or a 2-D position)
  std::vector<int64_t> y_shape;  ///< environment observation y: {m} or {C, H, W}
  int b_dim = 0;                 ///< beacon reading b (0 when no beacon is placed)
  int u_dim = 0;                 ///< action u

  bool YIsImage() const { return y_shape.size() == 3; }
  int64_t YSize() const;
  bool operator==(const DataSpec& other) const = default;
  /// Human-readable, e.g. "x 2, y 3x32x32, b 2, u 2".
  std::string ToString() const;
};

/// One time step of a demonstration: observation (x, y), beacon reading b, expert action u.
struct Sample {
  std::vector<float> x, y, b, u;
};

/// One demonstration, in time order.
struct Episode {
  std::vector<Sample> samples;
};

/// Play data: an observation with its beacon reading, recorded without a demonstration.
/// x is kept (the robot state at the time) because the feature network may read it.
struct PlaySample {
  std::vector<float> x, y, b;
};

/// Everything a learner is trained on.
struct Dataset {
  DataSpec spec;
  std::vector<Episode> demos;
  std::vector<PlaySample> play;
  /// How the play samples were recorded: consecutive chunks of these sizes, each in one scene
  /// (the marked objects where they were for it). Empty when unknown: each sample then stands
  /// alone. Used to smooth beacon readings within a chunk (TrainConfig::beacon_filter_samples)
  /// and to pair play samples of one chunk (TrainConfig::play_consistency).
  std::vector<int> play_chunks;

  int64_t NumDemoSamples() const;
};

/// Checks sizes against the spec and that every value is finite. Throws UserError naming the
/// episode, sample and field of the first problem (`source` names the origin, e.g. a file).
void ValidateDataset(const Dataset& dataset, const std::string& source = "dataset");

/// A stable 64-bit fingerprint of the dataset's shapes and values (FNV-1a over the bytes), stored
/// in checkpoints so that resuming on different data is caught.
uint64_t Fingerprint(const Dataset& dataset);

}  // namespace recon
