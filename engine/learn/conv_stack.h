#pragma once

// Forward and backward passes of the feature CNN's convolution blocks (conv + bias, 2x2 max-pool,
// ReLU) on a batch of images.
//
// A convolution is computed as a matrix product whose k-th "row" is the input plane shifted by
// tap k (c, ky, kx): output position p = oy * in_w + ox reads input p + c * in_h * in_w +
// ky * in_w + kx. Positions with ox >= out_w are computed but never used ("wide" planes), which
// keeps every row contiguous so that no im2col copy is needed.

#include <cstdint>
#include <vector>

#include "engine/learn/aligned_buffer.h"
#include "engine/learn/architecture.h"

namespace recon::learn {

/// Buffers of one convolution block for one batch.
struct ConvBuffers {
  int64_t conv_stride = 0;    ///< floats per output plane (out_h rows of in_w, rounded up)
  int64_t grad_front = 0;     ///< zeros before each gradient plane, so shifted reads stay in it
  int64_t grad_stride = 0;    ///< floats per gradient plane (front pad + in_h * in_w, rounded up)
  std::vector<int64_t> taps;  ///< input offset of tap (c, ky, kx)
  std::vector<int64_t> grad_taps;  ///< gradient-plane offset of (oc, ky, kx), for input gradients
  AlignedFloats conv;              ///< [batch][out_channels][conv_stride]
  AlignedFloats pooled;            ///< [batch][out_channels][pool_h * pool_w]
  AlignedFloats arg;               ///< winner of each pooling window (0..3)
  AlignedFloats grad_pooled;       ///< gradient w.r.t. pooled
  AlignedFloats grad_conv;         ///< [batch][out_channels][grad_stride]
  AlignedFloats weight_t;          ///< weights as [in][out * k * k], for input gradients
};

/// Buffers of all convolution blocks.
struct ConvStackBuffers {
  int batch = 0;
  std::vector<ConvBuffers> layers;

  void Resize(const std::vector<ConvLayer>& convs, int batch_size);
  /// Output of the last block: [batch][channels * pool_h * pool_w], the flattened CNN features.
  const float* output() const { return layers.back().pooled.data(); }
  /// Gradient w.r.t. output(); the caller fills it before ConvStackBackward.
  float* grad_output() { return layers.back().grad_pooled.data(); }
};

/// images[b] points at image b, channels-first, already multiplied by image_scale.
void ConvStackForward(const std::vector<ConvLayer>& convs, const float* params,
                      const float* const* images, ConvStackBuffers& buffers);

/// Adds the weight and bias gradients to `grads`, given grad_output() and a preceding forward
/// pass on the same images. `grad_images` (optional, [batch][in_channels * in_h * in_w]) receives
/// the gradient w.r.t. the images as they were passed (already scaled), overwritten: what a
/// saliency map is made of.
void ConvStackBackward(const std::vector<ConvLayer>& convs, const float* params,
                       const float* const* images, ConvStackBuffers& buffers, float* grads,
                       float* grad_images = nullptr);

}  // namespace recon::learn
