#include "engine/learn/gate_targets.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace recon::learn {

namespace {

// How many steps apart two demonstrations may do the same thing and still agree.
constexpr int64_t kTimingTolerance_steps = 5;

// The variance of each of the first `dim` values of every row (`width` values a row).
std::vector<double> ColumnVariances(const std::vector<float>& values, int64_t rows, int64_t width,
                                    int dim) {
  std::vector<double> mean(dim, 0.0), square(dim, 0.0), variance(dim, 0.0);
  for (int64_t r = 0; r < rows; ++r) {
    for (int d = 0; d < dim; ++d) {
      const double v = values[r * width + d];
      mean[d] += v;
      square[d] += v * v;
    }
  }
  for (int d = 0; d < dim; ++d) {
    const double m = mean[d] / static_cast<double>(rows);
    variance[d] = square[d] / static_cast<double>(rows) - m * m;
  }
  return variance;
}

// Per-dimension 1 / standard deviation of the demonstration states (0 for constant dimensions,
// which then do not count in the distance).
std::vector<double> InverseSpread(const TrainingData& data) {
  const int dim = data.spec.x_dim;
  std::vector<double> inverse = ColumnVariances(data.demo_x, data.num_demo, dim, dim);
  for (double& v : inverse) v = v > 1e-12 ? 1.0 / std::sqrt(v) : 0.0;
  return inverse;
}

// Each action dimension's weight in a squared difference of stored actions: it weighs by its
// units, not by its spread (differences in the user's units, stored * scale, over the actions'
// total variance in those units). Standardising each dimension instead would make a wrist joint
// that hardly moves weigh as much as the joint that carries the arm, and its small corrections
// look like disagreement.
std::vector<double> ActionWeights(const TrainingData& data,
                                  const std::vector<float>& action_scale) {
  const int u_dim = data.spec.u_dim;
  // Of each row's first action.
  const std::vector<double> variance = ColumnVariances(
      data.demo_u, data.num_demo, static_cast<int64_t>(u_dim) * data.action_chunk, u_dim);
  auto squared_scale = [&](int d) {
    const double scale = action_scale.empty() ? 1.0 : action_scale[d];
    return scale * scale;
  };
  double total = 0;
  for (int d = 0; d < u_dim; ++d) total += std::max(variance[d], 0.0) * squared_scale(d);
  std::vector<double> weight(u_dim, 0.0);
  for (int d = 0; d < u_dim; ++d) weight[d] = total > 0 ? squared_scale(d) / total : 0.0;
  return weight;
}

// Episode e's rows are contiguous: [begins[e], begins[e + 1]); one more entry than episodes.
std::vector<int64_t> EpisodeBegins(const TrainingData& data) {
  const int64_t rows = data.num_demo;
  const int episodes = data.demo_episode.back() + 1;
  std::vector<int64_t> begin(episodes + 1, rows);
  for (int64_t r = rows - 1; r >= 0; --r) begin[data.demo_episode[r]] = r;
  for (int e = episodes - 1; e >= 0; --e) begin[e] = std::min(begin[e], begin[e + 1]);
  return begin;
}

}  // namespace

std::vector<float> DemonstrationDisagreement(const TrainingData& data,
                                             const std::vector<float>& action_scale) {
  const int64_t rows = data.num_demo;
  std::vector<float> out(static_cast<size_t>(rows), 0.0f);
  if (rows == 0) return out;
  const int dim = data.spec.x_dim, u_dim = data.spec.u_dim;
  const int64_t width = static_cast<int64_t>(u_dim) * data.action_chunk;
  const std::vector<double> inverse = InverseSpread(data);
  const std::vector<double> weight = ActionWeights(data, action_scale);
  const std::vector<int64_t> begin = EpisodeBegins(data);
  const int episodes = static_cast<int>(begin.size()) - 1;
  for (int64_t r = 0; r < rows; ++r) {
    const float* x = data.demo_x.data() + r * dim;
    const float* u = data.demo_u.data() + r * width;
    float largest = 0.0f;
    for (int e = 0; e < episodes; ++e) {
      if (e == data.demo_episode[r] || begin[e] == begin[e + 1]) continue;
      int64_t nearest = begin[e];
      double nearest_distance = std::numeric_limits<double>::infinity();
      for (int64_t q = begin[e]; q < begin[e + 1]; ++q) {
        const float* y = data.demo_x.data() + q * dim;
        double distance = 0;
        for (int d = 0; d < dim; ++d) {
          const double diff = (x[d] - y[d]) * inverse[d];
          distance += diff * diff;
        }
        if (distance < nearest_distance) {
          nearest_distance = distance;
          nearest = q;
        }
      }
      // The same actions a few steps earlier or later are agreement: timing is not what the
      // camera tells (e.g. when the fingers close), so the best-matching row near the nearest one.
      double closest = std::numeric_limits<double>::infinity();
      const int64_t first = std::max(begin[e], nearest - kTimingTolerance_steps);
      const int64_t last = std::min(begin[e + 1] - 1, nearest + kTimingTolerance_steps);
      for (int64_t q = first; q <= last; ++q) {
        const float* v = data.demo_u.data() + q * width;
        double squared = 0;
        for (int64_t i = 0; i < width; ++i) {
          squared += weight[i % u_dim] * (u[i] - v[i]) * (u[i] - v[i]);
        }
        closest = std::min(closest, squared);
      }
      largest = std::max(largest, static_cast<float>(closest / data.action_chunk));
    }
    out[static_cast<size_t>(r)] = largest;
  }
  return out;
}

std::vector<float> DisagreementGateTargets(const TrainingData& data,
                                           const std::vector<float>& action_scale, double margin) {
  std::vector<float> targets = DemonstrationDisagreement(data, action_scale);
  for (float& t : targets) t = t > margin ? 1.0f : 0.0f;
  // A disagreement over fewer than two chunks' rows is dropped: a choice the camera decides
  // (which plate) shapes the rest of the trajectory, while one action that differs already
  // marks a chunk's rows, and a few such actions are timing (when the fingers close) that the
  // tolerance did not absorb.
  const int64_t shortest = 2 * static_cast<int64_t>(data.action_chunk);
  int64_t r = 0;
  while (r < data.num_demo) {
    if (targets[r] == 0.0f) {
      ++r;
      continue;
    }
    int64_t end = r;  // the run of marked rows from r, within r's episode
    while (end < data.num_demo && targets[end] == 1.0f &&
           data.demo_episode[end] == data.demo_episode[r]) {
      ++end;
    }
    if (end - r < shortest) std::fill(targets.begin() + r, targets.begin() + end, 0.0f);
    r = end;
  }
  return targets;
}

}  // namespace recon::learn
