#include "engine/learn/target_scaling.h"

#include <cmath>

#include "engine/core/error.h"
#include "engine/learn/training_data.h"

namespace recon::learn {

namespace {

// Below this spread a dimension is treated as constant (scale 1): dividing by a tiny spread
// would blow rounding noise up into targets.
constexpr double kMinSpread = 1e-6;

void FitColumns(const std::vector<const std::vector<float>*>& sources, int dim,
                std::vector<float>& offset, std::vector<float>& scale) {
  offset.assign(dim, 0.0f);
  scale.assign(dim, 1.0f);
  for (int k = 0; k < dim; ++k) {
    double sum = 0.0, sum_sq = 0.0;
    int64_t n = 0;
    for (const std::vector<float>* values : sources) {
      for (size_t i = k; i < values->size(); i += dim) {
        sum += (*values)[i];
        sum_sq += static_cast<double>((*values)[i]) * (*values)[i];
        ++n;
      }
    }
    if (n == 0) continue;
    const double mean = sum / static_cast<double>(n);
    const double variance = std::max(0.0, sum_sq / static_cast<double>(n) - mean * mean);
    const double spread = std::sqrt(variance);
    offset[k] = static_cast<float>(mean);
    if (spread > kMinSpread) scale[k] = static_cast<float>(spread);
  }
}

void Standardise(std::vector<float>& values, const std::vector<float>& offset,
                 const std::vector<float>& scale) {
  const size_t dim = offset.size();
  if (dim == 0) return;
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] = (values[i] - offset[i % dim]) / scale[i % dim];
  }
}

// `width` values per row, a multiple of the offsets' size (a chunk of several actions).
void Restore(float* rows, int count, int stride, int width, const std::vector<float>& offset,
             const std::vector<float>& scale) {
  const size_t dim = offset.size();
  if (dim == 0) return;
  for (int r = 0; r < count; ++r) {
    float* row = rows + static_cast<size_t>(r) * stride;
    for (size_t k = 0; k < static_cast<size_t>(width); ++k) {
      row[k] = row[k] * scale[k % dim] + offset[k % dim];
    }
  }
}

}  // namespace

TargetScaling TargetScaling::Identity(const DataSpec& spec) {
  TargetScaling t;
  t.u_offset.assign(spec.u_dim, 0.0f);
  t.u_scale.assign(spec.u_dim, 1.0f);
  t.b_offset.assign(spec.b_dim, 0.0f);
  t.b_scale.assign(spec.b_dim, 1.0f);
  return t;
}

TargetScaling TargetScaling::Fit(const TrainingData& data) {
  TargetScaling t;
  FitColumns({&data.demo_u}, data.spec.u_dim, t.u_offset, t.u_scale);
  FitColumns({&data.demo_b, &data.play_b}, data.spec.b_dim, t.b_offset, t.b_scale);
  return t;
}

void TargetScaling::FitInputs(const TrainingData& data) {
  FitColumns({&data.demo_x, &data.play_x}, data.spec.x_dim, x_offset, x_scale);
  if (data.spec.YIsImage()) return;
  const int y_dim = static_cast<int>(data.y_size);
  const std::vector<float> demo_y(data.demo_y.begin(), data.demo_y.end());
  const std::vector<float> play_y(data.play_y.begin(), data.play_y.end());
  FitColumns({&demo_y, &play_y}, y_dim, y_offset, y_scale);
}

void TargetScaling::ApplyToInputs(float* x, float* y) const {
  if (x != nullptr) {
    for (size_t k = 0; k < x_offset.size(); ++k) x[k] = (x[k] - x_offset[k]) / x_scale[k];
  }
  if (y == nullptr) return;
  for (size_t k = 0; k < y_offset.size(); ++k) y[k] = (y[k] - y_offset[k]) / y_scale[k];
}

void TargetScaling::Apply(TrainingData& data) const {
  Standardise(data.demo_u, u_offset, u_scale);
  Standardise(data.demo_b, b_offset, b_scale);
  Standardise(data.play_b, b_offset, b_scale);
  Standardise(data.demo_x, x_offset, x_scale);
  Standardise(data.play_x, x_offset, x_scale);
  if (!y_offset.empty()) {
    for (int64_t i = 0; i < data.num_demo; ++i) {
      ApplyToInputs(nullptr, data.demo_y.data() + i * data.y_size);
    }
    for (int64_t i = 0; i < data.num_play; ++i) {
      ApplyToInputs(nullptr, data.play_y.data() + i * data.y_size);
    }
  }
}

void TargetScaling::RestoreActions(float* rows, int count, int stride, int width) const {
  Restore(rows, count, stride, width < 0 ? static_cast<int>(u_offset.size()) : width, u_offset,
          u_scale);
}

void TargetScaling::RestoreBeacons(float* rows, int count, int stride) const {
  Restore(rows, count, stride, static_cast<int>(b_offset.size()), b_offset, b_scale);
}

std::vector<float> TargetScaling::Flatten() const {
  std::vector<float> flat;
  for (const std::vector<float>* v :
       {&u_offset, &u_scale, &b_offset, &b_scale, &x_offset, &x_scale, &y_offset, &y_scale}) {
    flat.insert(flat.end(), v->begin(), v->end());
  }
  return flat;
}

TargetScaling TargetScaling::Unflatten(const DataSpec& spec, const std::vector<float>& flat) {
  const size_t u = spec.u_dim, b = spec.b_dim, x = spec.x_dim;
  const size_t y = spec.YIsImage() ? 0 : static_cast<size_t>(spec.YSize());
  // Targets only (every checkpoint before input scaling, and those trained without it), or
  // targets and inputs.
  const bool inputs = flat.size() == 2 * (u + b + x + y);
  if (flat.size() != 2 * (u + b) && !inputs) {
    throw UserError("target scaling holds " + std::to_string(flat.size()) + " values, expected " +
                    std::to_string(2 * (u + b)) + " (targets) or " +
                    std::to_string(2 * (u + b + x + y)) + " (targets and inputs)");
  }
  for (float v : flat) {
    if (!std::isfinite(v)) throw UserError("target scaling holds a non-finite value");
  }
  TargetScaling t;
  auto take = [&, pos = size_t{0}](size_t n) mutable {
    std::vector<float> out(flat.begin() + pos, flat.begin() + pos + n);
    pos += n;
    return out;
  };
  t.u_offset = take(u);
  t.u_scale = take(u);
  t.b_offset = take(b);
  t.b_scale = take(b);
  if (inputs) {
    t.x_offset = take(x);
    t.x_scale = take(x);
    t.y_offset = take(y);
    t.y_scale = take(y);
  }
  return t;
}

}  // namespace recon::learn
