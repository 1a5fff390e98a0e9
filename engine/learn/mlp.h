#pragma once

// Forward and backward passes of a stack of fully connected layers on a batch.

#include <vector>

#include "engine/learn/aligned_buffer.h"
#include "engine/learn/architecture.h"

namespace recon::learn {

/// Activations and gradients of one MLP for one batch (sized by Resize).
struct MlpBuffers {
  int batch = 0;
  std::vector<AlignedFloats> out;   ///< per layer: activation output, [batch][out]
  std::vector<AlignedFloats> grad;  ///< per layer: gradient w.r.t. the pre-activation output

  void Resize(const std::vector<LinearLayer>& layers, int batch_size);
  const float* output() const { return out.back().data(); }
};

/// input: [batch][layers[0].in].
void MlpForward(const std::vector<LinearLayer>& layers, const float* params, const float* input,
                MlpBuffers& buffers);

/// Backpropagates grad_output ([batch][last out]) through the layers after MlpForward on the
/// same input: adds the weight and bias gradients to `grads` (flat, like params) and, if
/// grad_input is not null, writes the gradient w.r.t. the input ([batch][layers[0].in]).
void MlpBackward(const std::vector<LinearLayer>& layers, const float* params, const float* input,
                 const float* grad_output, MlpBuffers& buffers, float* grads, float* grad_input);

}  // namespace recon::learn
