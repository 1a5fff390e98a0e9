#pragma once

// The dataset stacked into contiguous arrays, so that a batch is a set of row pointers and a
// few tiny copies rather than a gather of images.

#include <cstdint>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/learn/aligned_buffer.h"

namespace recon::learn {

/// Demonstration and play samples as row-major arrays. Images are stored multiplied by the
/// network's image_scale, so the networks read them in place.
struct TrainingData {
  DataSpec spec;
  int64_t num_demo = 0, num_play = 0;
  int64_t y_size = 0;
  int action_chunk = 1;
  std::vector<float> demo_x, demo_b, demo_u, play_x, play_b;  ///< demo_u: u_dim * action_chunk
  std::vector<int32_t> demo_episode;  ///< per demonstration row, its episode's index
  AlignedFloats demo_y, play_y;
  uint64_t fingerprint = 0;  ///< Fingerprint() of the source dataset

  /// `action_chunk` > 1 stores each demonstration row's target as the next action_chunk actions
  /// of its episode (u_t .. u_{t+k-1}, the last one repeated past the episode's end).
  static TrainingData From(const Dataset& dataset, float image_scale, int action_chunk = 1);

  const float* DemoY(int64_t i) const { return demo_y.data() + i * y_size; }
  const float* PlayY(int64_t i) const { return play_y.data() + i * y_size; }
};

}  // namespace recon::learn
