#pragma once

// Forward and backward passes of the spatial softmax (SpatialSoftmaxLayer, architecture.h) on a
// batch: 2 keypoint coordinates per channel of the last convolution block's output.
//
// Plain loops rather than a kernel table entry: a plane holds a few dozen values after two
// pooling steps, so this layer costs a small fraction of the convolutions that feed it.

#include <vector>

#include "engine/learn/aligned_buffer.h"
#include "engine/learn/architecture.h"

namespace recon::learn {

/// The coordinates of n pixel centres spread over [-1, 1] (first -1, last +1; 0 if n = 1),
/// which is numpy's linspace(-1, 1, n) as robomimic uses it.
std::vector<float> KeypointCoordinates(int n);

/// Activations of one batch (sized by Resize, so a step allocates nothing).
struct SpatialSoftmaxBuffers {
  int batch = 0;
  std::vector<float> x_coord;  ///< per column
  std::vector<float> y_coord;  ///< per row
  AlignedFloats softmax;       ///< [batch][channels][h * w], kept for the backward pass
  AlignedFloats plane_max;     ///< [batch][channels]: max of f / T, which the softmax subtracts
  AlignedFloats out;           ///< [batch][2 * channels]: x_0, y_0, x_1, y_1, ...
  AlignedFloats grad_out;      ///< gradient w.r.t. out; the caller fills it before Backward

  void Resize(const SpatialSoftmaxLayer& layer, int batch_size);
  const float* output() const { return out.data(); }
  float* grad_output() { return grad_out.data(); }
};

/// input: [batch][channels][h * w], planes row-major (the convolution stack's output).
void SpatialSoftmaxForward(const SpatialSoftmaxLayer& layer, const float* params,
                           const float* input, SpatialSoftmaxBuffers& buffers);

/// After a forward pass on the same input and with grad_output() filled: writes the gradient
/// w.r.t. the input to grad_input ([batch][channels][h * w]) and adds that of log T to `grads`.
void SpatialSoftmaxBackward(const SpatialSoftmaxLayer& layer, const float* params,
                            const float* input, SpatialSoftmaxBuffers& buffers, float* grads,
                            float* grad_input);

}  // namespace recon::learn
