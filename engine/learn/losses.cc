#include "engine/learn/losses.h"

#include <cmath>

namespace recon::learn {

namespace {
constexpr double kLog2Pi = 1.8378770664093453;  // log(2 pi)
}

float GaussianNll(const float* head, const float* target, int batch, int dim, float weight,
                  float* grad_head, const float* min_logvar) {
  double total = 0;
  const float scale = weight / static_cast<float>(batch);
  for (int b = 0; b < batch; ++b) {
    const float* mean = head + static_cast<int64_t>(b) * 2 * dim;
    const float* logvar = mean + dim;
    const float* t = target + static_cast<int64_t>(b) * dim;
    for (int d = 0; d < dim; ++d) {
      const float diff = t[d] - mean[d];
      const bool floored = min_logvar != nullptr && logvar[d] < min_logvar[d];
      const float v = floored ? min_logvar[d] : logvar[d];
      const float inv_var = std::exp(-v);
      const float sq = diff * diff * inv_var;
      total += 0.5 * (kLog2Pi + v + sq);
      if (grad_head != nullptr) {
        float* g = grad_head + static_cast<int64_t>(b) * 2 * dim;
        g[d] = scale * (-diff * inv_var);
        g[dim + d] = floored ? 0.0f : scale * 0.5f * (1.0f - sq);
      }
    }
  }
  return static_cast<float>(total / batch);
}

float MseOfSample(const float* head, const float* target, const float* noise, int batch, int dim,
                  float weight, float* grad_head) {
  double total = 0;
  const int64_t count = static_cast<int64_t>(batch) * dim;
  const float scale = weight * 2.0f / static_cast<float>(count);
  for (int b = 0; b < batch; ++b) {
    const float* mean = head + static_cast<int64_t>(b) * 2 * dim;
    const float* logvar = mean + dim;
    const float* t = target + static_cast<int64_t>(b) * dim;
    const float* eps = noise + static_cast<int64_t>(b) * dim;
    for (int d = 0; d < dim; ++d) {
      const float std_dev = std::exp(0.5f * logvar[d]);
      const float diff = mean[d] + std_dev * eps[d] - t[d];
      total += static_cast<double>(diff) * diff;
      if (grad_head != nullptr) {
        float* g = grad_head + static_cast<int64_t>(b) * 2 * dim;
        const float ds = scale * diff;
        g[d] = ds;
        g[dim + d] = ds * eps[d] * 0.5f * std_dev;
      }
    }
  }
  return static_cast<float>(total / static_cast<double>(count));
}

float HeadLoss(LossKind kind, const float* head, const float* target, const float* noise, int batch,
               int dim, float weight, float* grad_head, const float* min_logvar) {
  return kind == LossKind::kNll
             ? GaussianNll(head, target, batch, dim, weight, grad_head, min_logvar)
             : MseOfSample(head, target, noise, batch, dim, weight, grad_head);
}

double SumSquaredMeanError(const float* head, const float* target, int batch, int dim) {
  double total = 0;
  for (int b = 0; b < batch; ++b) {
    const float* mean = head + static_cast<int64_t>(b) * 2 * dim;
    const float* t = target + static_cast<int64_t>(b) * dim;
    for (int d = 0; d < dim; ++d) {
      const double diff = static_cast<double>(mean[d]) - t[d];
      total += diff * diff;
    }
  }
  return total;
}

}  // namespace recon::learn
