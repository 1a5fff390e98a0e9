#pragma once

// The whole model's forward and backward passes on one batch: feature net -> phi, policy on
// [x, phi], beacon net on phi. Parameters and gradients are flat buffers laid out by
// Architecture; the caller owns them (the trainer, or a Policy's copy).

#include <vector>

#include "engine/learn/architecture.h"
#include "engine/learn/conv_stack.h"
#include "engine/learn/mlp.h"
#include "engine/learn/spatial_softmax.h"

namespace recon::learn {

/// Inputs, activations and gradients of one batch. The caller fills `x` and `y`, then runs the
/// forward functions it needs, then Backward.
struct ModelBuffers {
  int batch = 0;
  std::vector<float> x;             ///< [batch][x_dim]
  std::vector<const float*> y;      ///< per sample: the image (times image_scale) or the vector y
  ConvStackBuffers convs;           ///< image feature net only
  SpatialSoftmaxBuffers keypoints;  ///< image feature net with Architecture::spatial_softmax
  std::vector<float> mlp_input;     ///< vector feature net only: [batch][x_dim + m]
  MlpBuffers feature, policy, beacon;
  std::vector<float> policy_input, grad_policy_input, grad_beacon_input, grad_phi;

  void Resize(const Architecture& arch, int batch_size);
  const float* phi() const { return feature.output(); }
  const float* policy_head() const { return policy.output(); }  ///< [batch][mean u | logvar u]
  const float* beacon_head() const { return beacon.output(); }  ///< [batch][mean d | logvar d]
};

void ForwardFeatures(const Architecture& arch, const float* params, ModelBuffers& buffers);
/// `phi_offsets` ([batch][k], optional) are added to phi in the policy's input only (feature
/// noise, TrainConfig::feature_noise): the beacon net still reads the features clean.
void ForwardPolicy(const Architecture& arch, const float* params, ModelBuffers& buffers,
                   const float* phi_offsets = nullptr);
void ForwardBeacon(const Architecture& arch, const float* params, ModelBuffers& buffers);

/// Backpropagates the given head gradients (either may be null if that head was not used) and
/// adds all parameter gradients to `grads`.
void Backward(const Architecture& arch, const float* params, const float* grad_policy_head,
              const float* grad_beacon_head, ModelBuffers& buffers, float* grads);

}  // namespace recon::learn
