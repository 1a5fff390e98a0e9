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
  // The feature gate (Architecture::gate) only: the gate net, the policy's blind branch on
  // [x, 0], and the acting head, the gate's mixture of the two branches' heads.
  MlpBuffers gate, policy_blind;
  std::vector<float> blind_input;  ///< [batch][x_dim + k]: x, then zeros
  std::vector<float> gate_value;   ///< [batch]: g(x) = sigmoid(gate net output)
  std::vector<float> grad_gate;    ///< [batch]: gradient w.r.t. the gate net's output (caller's)
  std::vector<float> policy_mix;   ///< [batch][2 * action width]

  void Resize(const Architecture& arch, int batch_size);
  const float* phi() const { return feature.output(); }
  /// [batch][mean u | logvar u] the robot acts on: the seeing branch's head, or with a feature
  /// gate the mixture g seeing + (1 - g) blind (means and log-variances alike).
  const float* policy_head() const {
    return gate_value.empty() ? policy.output() : policy_mix.data();
  }
  float* mutable_policy_head() {
    return gate_value.empty() ? policy.out.back().data() : policy_mix.data();
  }
  /// The two branches' own heads (with a feature gate; seeing = policy_head() without one).
  const float* seeing_head() const { return policy.output(); }
  const float* blind_head() const { return policy_blind.output(); }
  const float* beacon_head() const { return beacon.output(); }  ///< [batch][mean d | logvar d]
};

void ForwardFeatures(const Architecture& arch, const float* params, ModelBuffers& buffers);
/// `phi_offsets` ([batch][k], optional) are added to phi in the policy's input only (feature
/// noise, TrainConfig::feature_noise): the beacon net still reads the features clean. With a
/// feature gate it also runs the gate and the policy's blind branch, and mixes the heads.
void ForwardPolicy(const Architecture& arch, const float* params, ModelBuffers& buffers,
                   const float* phi_offsets = nullptr);
void ForwardBeacon(const Architecture& arch, const float* params, ModelBuffers& buffers);

/// Backpropagates the given head gradients (either may be null if that head was not used) and
/// adds all parameter gradients to `grads`. With a feature gate, grad_policy_head is the seeing
/// branch's, `grad_blind_head` the blind branch's, and the caller has filled buffers.grad_gate.
/// `grad_phi_extra` ([batch][k], optional) is a loss's gradient on the features themselves
/// (TrainConfig::play_consistency).
/// `grad_images` (optional, image feature nets only: [batch][3 S S]) receives the gradient
/// w.r.t. the images the CNN read (y times image_scale), overwritten.
void Backward(const Architecture& arch, const float* params, const float* grad_policy_head,
              const float* grad_beacon_head, ModelBuffers& buffers, float* grads,
              const float* grad_blind_head = nullptr, const float* grad_phi_extra = nullptr,
              float* grad_images = nullptr);

}  // namespace recon::learn
