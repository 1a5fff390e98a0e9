#include "engine/learn/play_consistency.h"

#include <algorithm>

namespace recon::learn {

PlayChunks PlayChunks::FromGroups(const std::vector<int32_t>& group) {
  const int64_t rows = static_cast<int64_t>(group.size());
  PlayChunks chunks;
  chunks.first.resize(static_cast<size_t>(rows));
  chunks.size.resize(static_cast<size_t>(rows));
  int64_t begin = 0;
  while (begin < rows) {
    int64_t end = begin + 1;
    while (end < rows && group[end] == group[begin]) ++end;
    for (int64_t row = begin; row < end; ++row) {
      chunks.first[row] = begin;
      chunks.size[row] = static_cast<int32_t>(end - begin);
    }
    begin = end;
  }
  return chunks;
}

int64_t PlayChunks::Partner(int64_t row, Rng& rng) const {
  const int32_t n = size[row];
  if (n <= 1) return row;
  // A uniform draw among the chunk's other n - 1 rows.
  const int64_t offset = static_cast<int64_t>(rng.UniformInt(static_cast<uint64_t>(n - 1)));
  const int64_t other = first[row] + offset;
  return other >= row ? other + 1 : other;
}

float PlayConsistencyLoss(const float* phi, int batch, int k, float weight, float* grad_phi) {
  std::fill_n(grad_phi, static_cast<size_t>(batch) * k, 0.0f);
  const int pairs = batch / 2;
  if (pairs == 0) return 0.0f;
  std::vector<double> mean(static_cast<size_t>(k), 0.0);
  for (int b = 0; b < batch; ++b) {
    for (int j = 0; j < k; ++j) mean[j] += phi[static_cast<size_t>(b) * k + j];
  }
  for (double& m : mean) m /= batch;
  double variance = 0;  // summed over the k features
  for (int b = 0; b < batch; ++b) {
    for (int j = 0; j < k; ++j) {
      const double centred = phi[static_cast<size_t>(b) * k + j] - mean[j];
      variance += centred * centred;
    }
  }
  variance /= batch;
  double distance = 0;  // mean over pairs of the squared distance
  for (int p = 0; p < pairs; ++p) {
    const float* a = phi + static_cast<size_t>(2 * p) * k;
    const float* b = a + k;
    for (int j = 0; j < k; ++j) distance += (a[j] - b[j]) * static_cast<double>(a[j] - b[j]);
  }
  distance /= pairs;
  const double spread = 2 * variance + kPlayConsistencySpreadFloor;
  const double loss = distance / spread;
  // d(distance / spread) = d distance / spread - loss * d spread / spread, where
  // d distance / d a = 2 (a - b) / pairs (and the opposite for b) and
  // d spread / d phi_bj = 4 (phi_bj - mean_j) / batch (the mean's own change sums to zero).
  const double pair_scale = weight * 2.0 / (pairs * spread);
  const double spread_scale = weight * loss * 4.0 / (batch * spread);
  for (int b = 0; b < batch; ++b) {
    for (int j = 0; j < k; ++j) {
      const size_t at = static_cast<size_t>(b) * k + j;
      grad_phi[at] = static_cast<float>(-spread_scale * (phi[at] - mean[j]));
    }
  }
  for (int p = 0; p < pairs; ++p) {
    const size_t a = static_cast<size_t>(2 * p) * k, b = a + k;
    for (int j = 0; j < k; ++j) {
      const double d = pair_scale * (phi[a + j] - phi[b + j]);
      grad_phi[a + j] += static_cast<float>(d);
      grad_phi[b + j] -= static_cast<float>(d);
    }
  }
  return static_cast<float>(loss);
}

}  // namespace recon::learn
