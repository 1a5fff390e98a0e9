#include "engine/learn/spatial_softmax.h"

#include <cmath>

namespace recon::learn {

std::vector<float> KeypointCoordinates(int n) {
  std::vector<float> coords(n, 0.0f);
  for (int i = 0; i < n && n > 1; ++i) coords[i] = static_cast<float>(-1.0 + 2.0 * i / (n - 1));
  return coords;
}

void SpatialSoftmaxBuffers::Resize(const SpatialSoftmaxLayer& layer, int batch_size) {
  batch = batch_size;
  x_coord = KeypointCoordinates(layer.w);
  y_coord = KeypointCoordinates(layer.h);
  const size_t planes = static_cast<size_t>(batch) * layer.channels;
  softmax.assign(planes * layer.h * layer.w, 0.0f);
  plane_max.assign(planes, 0.0f);
  out.assign(2 * planes, 0.0f);
  grad_out.assign(2 * planes, 0.0f);
}

void SpatialSoftmaxForward(const SpatialSoftmaxLayer& layer, const float* params,
                           const float* input, SpatialSoftmaxBuffers& buffers) {
  const int h = layer.h, w = layer.w, hw = h * w;
  // Multiplying by 1 / T, as the Torch backend does, keeps the two backends' rounding alike.
  const float inv_t = std::exp(-params[layer.log_temperature]);
  const int planes = buffers.batch * layer.channels;
  for (int p = 0; p < planes; ++p) {
    const float* f = input + static_cast<int64_t>(p) * hw;
    float* s = buffers.softmax.data() + static_cast<int64_t>(p) * hw;
    // Subtracting the largest logit keeps exp() from overflowing on raw 0-255 features. A NaN
    // becomes the maximum, so it spreads through the sums and reaches the loss, where it is
    // reported like everywhere else.
    float m = f[0] * inv_t;
    for (int i = 1; i < hw; ++i) {
      const float z = f[i] * inv_t;
      m = z > m || std::isnan(z) ? z : m;
    }
    float sum = 0.0f;
    for (int i = 0; i < hw; ++i) {
      s[i] = std::exp(f[i] * inv_t - m);
      sum += s[i];
    }
    const float inv_sum = 1.0f / sum;
    float ex = 0.0f, ey = 0.0f;
    for (int r = 0; r < h; ++r) {
      float row = 0.0f;
      for (int c = 0; c < w; ++c) {
        const float v = s[r * w + c] * inv_sum;
        s[r * w + c] = v;
        ex += v * buffers.x_coord[c];
        row += v;
      }
      ey += row * buffers.y_coord[r];
    }
    buffers.plane_max[p] = m;
    buffers.out[2 * p] = ex;
    buffers.out[2 * p + 1] = ey;
  }
}

void SpatialSoftmaxBackward(const SpatialSoftmaxLayer& layer, const float* params,
                            const float* input, SpatialSoftmaxBuffers& buffers, float* grads,
                            float* grad_input) {
  const int h = layer.h, w = layer.w, hw = h * w;
  const float inv_t = std::exp(-params[layer.log_temperature]);
  const int planes = buffers.batch * layer.channels;
  // With z = f / T and a = dL/dz = s (g_x (x - E[x]) + g_y (y - E[y])): dL/df = a / T, and
  // dL/dlog T = -sum a z. Since sum a = 0, z may be taken relative to the plane's maximum,
  // which removes the large common part of raw-pixel logits before the sum.
  double grad_log_t = 0.0;
  for (int p = 0; p < planes; ++p) {
    const float* f = input + static_cast<int64_t>(p) * hw;
    const float* s = buffers.softmax.data() + static_cast<int64_t>(p) * hw;
    float* g = grad_input + static_cast<int64_t>(p) * hw;
    const float gx = buffers.grad_out[2 * p], gy = buffers.grad_out[2 * p + 1];
    const float ex = buffers.out[2 * p], ey = buffers.out[2 * p + 1];
    const float m = buffers.plane_max[p];
    float plane_sum = 0.0f;
    for (int r = 0; r < h; ++r) {
      const float dy = gy * (buffers.y_coord[r] - ey);
      for (int c = 0; c < w; ++c) {
        const int i = r * w + c;
        const float a = s[i] * (gx * (buffers.x_coord[c] - ex) + dy);
        g[i] = a * inv_t;
        plane_sum += a * (f[i] * inv_t - m);
      }
    }
    grad_log_t -= plane_sum;
  }
  grads[layer.log_temperature] += static_cast<float>(grad_log_t);
}

}  // namespace recon::learn
