#include "engine/probe/saliency.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "engine/core/color_scale.h"
#include "engine/core/error.h"

namespace recon::probe {

namespace {

SaliencyMap EmptyMap(const learn::Policy& policy) {
  const std::vector<int64_t>& shape = policy.spec().y_shape;
  if (shape.size() != 3) throw UserError("the policy reads no camera image: it has no saliency");
  SaliencyMap map;
  map.height = static_cast<int>(shape[1]);
  map.width = static_cast<int>(shape[2]);
  map.value.assign(static_cast<size_t>(map.width) * map.height, 0.0f);
  return map;
}

void FindMax(SaliencyMap& map) {
  map.max = 0;
  for (float v : map.value) map.max = std::max(map.max, v);
}

}  // namespace

SaliencyMap GradientSaliency(const learn::Policy& policy, const std::vector<float>& x,
                             const std::vector<float>& y) {
  SaliencyMap map = EmptyMap(policy);
  const std::vector<std::vector<float>> jacobian = policy.ActionImageJacobian(x, y);
  const size_t plane = map.value.size();
  for (size_t p = 0; p < plane; ++p) {
    double sum = 0;
    for (const std::vector<float>& row : jacobian) {
      for (size_t c = 0; c < 3; ++c) {
        const double g = row[c * plane + p];
        sum += g * g;
      }
    }
    map.value[p] = static_cast<float>(std::sqrt(sum));
  }
  FindMax(map);
  return map;
}

SaliencyMap OcclusionSaliency(const learn::Policy& policy, const std::vector<float>& x,
                              const std::vector<float>& y, int patch, int stride) {
  const SaliencyMap shape = EmptyMap(policy);
  return OcclusionSaliency(
      [&policy](const std::vector<std::vector<float>>& xs,
                const std::vector<std::vector<float>>& ys) { return policy.ActBatch(xs, ys); },
      shape.width, x, y, patch, stride);
}

SaliencyMap OcclusionSaliency(const ActBatchFunction& act, int size, const std::vector<float>& x,
                              const std::vector<float>& y, int patch, int stride) {
  SaliencyMap map;
  map.width = map.height = size;
  map.value.assign(static_cast<size_t>(size) * size, 0.0f);
  if (patch < 1 || stride < 1 || patch > std::min(map.width, map.height)) {
    throw UserError("an occlusion patch is 1 to " +
                    std::to_string(std::min(map.width, map.height)) +
                    " pixels wide with a stride of at least 1, got " + std::to_string(patch) +
                    " and " + std::to_string(stride));
  }
  const size_t plane = map.value.size();
  if (y.size() != 3 * plane) {
    throw UserError("the image has " + std::to_string(y.size()) + " values, expected " +
                    std::to_string(3 * plane));
  }
  std::array<float, 3> mean = {0, 0, 0};
  for (size_t c = 0; c < 3; ++c) {
    double sum = 0;
    for (size_t p = 0; p < plane; ++p) sum += y[c * plane + p];
    mean[c] = static_cast<float>(sum / plane);
  }
  // Every patch position, the last ones flush with the far edges so the whole image is covered.
  const auto starts = [&](int extent) {
    std::vector<int> at;
    for (int s = 0; s + patch <= extent; s += stride) at.push_back(s);
    if (at.back() + patch < extent) at.push_back(extent - patch);
    return at;
  };
  const std::vector<int> rows = starts(map.height), columns = starts(map.width);
  std::vector<std::vector<float>> xs, ys;
  for (int r : rows) {
    for (int c : columns) {
      std::vector<float> occluded = y;
      for (int i = r; i < r + patch; ++i) {
        for (int j = c; j < c + patch; ++j) {
          for (size_t ch = 0; ch < 3; ++ch) {
            occluded[ch * plane + static_cast<size_t>(i) * map.width + j] = mean[ch];
          }
        }
      }
      xs.push_back(x);
      ys.push_back(std::move(occluded));
    }
  }
  // The unoccluded image last, in the same batch.
  xs.push_back(x);
  ys.push_back(y);
  std::vector<std::vector<float>> actions = act(xs, ys);
  const std::vector<float> base = actions.back();
  actions.pop_back();
  std::vector<int> covered(plane, 0);
  size_t k = 0;
  for (int r : rows) {
    for (int c : columns) {
      double change = 0;
      for (size_t j = 0; j < base.size(); ++j) {
        const double d = static_cast<double>(actions[k][j]) - base[j];
        change += d * d;
      }
      ++k;
      for (int i = r; i < r + patch; ++i) {
        for (int j = c; j < c + patch; ++j) {
          const size_t p = static_cast<size_t>(i) * map.width + j;
          map.value[p] += static_cast<float>(std::sqrt(change));
          ++covered[p];
        }
      }
    }
  }
  for (size_t p = 0; p < plane; ++p) {
    if (covered[p] > 0) map.value[p] /= static_cast<float>(covered[p]);
  }
  FindMax(map);
  return map;
}

RgbImage OverlaySaliency(const RgbImage& view, const SaliencyMap& map) {
  RgbImage out = view;
  if (map.max <= 0 || map.width <= 0 || map.height <= 0 || view.height <= 0) return out;
  const int side = std::min(view.width, view.height);
  const int left = (view.width - side) / 2, top = (view.height - side) / 2;
  constexpr double kMostOpaque = 0.7;  // the frame still shows through the most salient pixel
  for (int r = 0; r < side; ++r) {
    const int map_row = std::min(map.height - 1, r * map.height / side);
    for (int c = 0; c < side; ++c) {
      const int map_column = std::min(map.width - 1, c * map.width / side);
      // On a square-root scale: a gradient map is a few strong pixels among many weak but real
      // ones, which a linear scale would hide.
      const double t = std::sqrt(std::max(
          0.0, double(map.value[static_cast<size_t>(map_row) * map.width + map_column]) / map.max));
      const std::array<double, 3> colour = SequentialColor(t);
      const double alpha = kMostOpaque * std::clamp(t, 0.0, 1.0);
      uint8_t* px = out.rgb.data() + (static_cast<size_t>(top + r) * out.width + left + c) * 3;
      for (int k = 0; k < 3; ++k) {
        px[k] = static_cast<uint8_t>(std::lround((1 - alpha) * px[k] + alpha * 255 * colour[k]));
      }
    }
  }
  return out;
}

}  // namespace recon::probe
