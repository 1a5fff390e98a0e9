#include "engine/teach/stream_health.h"

#include <cmath>

#include "engine/core/error.h"

namespace recon::teach {

StreamHealth::StreamHealth(double expected_rate_hz, double window_s)
    : expected_rate_hz_(expected_rate_hz), window_s_(window_s) {
  if (!(expected_rate_hz > 0) || !(window_s > 0)) {
    throw UserError("a stream's expected rate and window must be positive");
  }
}

void StreamHealth::Add(double t_s, const std::vector<float>& reading) {
  updates_.push_back({t_s, reading});
  Forget(t_s);
}

void StreamHealth::Forget(double now_s) {
  while (!updates_.empty() && updates_.front().t_s < now_s - window_s_) updates_.pop_front();
}

StreamStats StreamHealth::Stats(double now_s) const {
  StreamStats stats;
  // Only updates inside the window count; older ones are dropped on the next Add.
  size_t first = 0;
  while (first < updates_.size() && updates_[first].t_s < now_s - window_s_) ++first;
  const size_t n = updates_.size() - first;
  stats.received = static_cast<int>(n);
  if (!updates_.empty()) stats.seconds_since_last = now_s - updates_.back().t_s;
  if (n == 0) {
    if (!updates_.empty()) stats.dropout_fraction = 1.0;  // it was streaming and stopped
    return stats;
  }
  // The rate over the window (a window not yet full counts from its first update).
  const double span = std::min(window_s_, now_s - updates_[first].t_s);
  stats.rate_hz = span > 0 ? (n - 1) / span : 0.0;
  // Updates missing in long gaps, including the gap since the last one.
  const double period = 1.0 / expected_rate_hz_;
  double missing = 0;
  const auto count_gap = [&](double gap) {
    if (gap > 1.5 * period) missing += std::round(gap / period) - 1;
  };
  for (size_t i = first + 1; i < updates_.size(); ++i) {
    count_gap(updates_[i].t_s - updates_[i - 1].t_s);
  }
  count_gap(now_s - updates_.back().t_s);
  stats.dropout_fraction = missing / (missing + static_cast<double>(n));
  // Noise: per-coordinate variance over the readings that have the first one's size.
  const size_t dim = updates_[first].reading.size();
  if (dim > 0 && n >= 2) {
    std::vector<double> mean(dim, 0.0), square(dim, 0.0);
    int used = 0;
    for (size_t i = first; i < updates_.size(); ++i) {
      const std::vector<float>& r = updates_[i].reading;
      if (r.size() != dim) continue;
      ++used;
      for (size_t k = 0; k < dim; ++k) mean[k] += r[k];
    }
    for (double& m : mean) m /= used;
    for (size_t i = first; i < updates_.size(); ++i) {
      const std::vector<float>& r = updates_[i].reading;
      if (r.size() != dim) continue;
      for (size_t k = 0; k < dim; ++k) square[k] += (r[k] - mean[k]) * (r[k] - mean[k]);
    }
    double variance = 0;
    for (double s : square) variance += s / (used - 1 > 0 ? used - 1 : 1);
    stats.noise = std::sqrt(variance);
  }
  return stats;
}

}  // namespace recon::teach
