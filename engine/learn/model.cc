#include "engine/learn/model.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace recon::learn {

void ModelBuffers::Resize(const Architecture& arch, int batch_size) {
  batch = batch_size;
  const size_t n = static_cast<size_t>(batch);
  const int x_dim = arch.spec.x_dim, k = arch.feature_dim();
  x.assign(n * x_dim, 0.0f);
  y.assign(n, nullptr);
  if (arch.image()) {
    convs.Resize(arch.convs, batch);
    if (arch.spatial_softmax) keypoints.Resize(arch.keypoints, batch);
  } else {
    mlp_input.assign(n * arch.feature.front().in, 0.0f);
  }
  feature.Resize(arch.feature, batch);
  policy.Resize(arch.policy, batch);
  policy_input.assign(n * (x_dim + k), 0.0f);
  grad_policy_input.assign(n * (x_dim + k), 0.0f);
  if (arch.has_beacon_net()) beacon.Resize(arch.beacon, batch);
  grad_beacon_input.assign(n * k, 0.0f);
  grad_phi.assign(n * k, 0.0f);
  if (arch.has_gate()) {
    gate.Resize(arch.gate, batch);
    policy_blind.Resize(arch.policy, batch);
    blind_input.assign(n * (x_dim + k), 0.0f);
    gate_value.assign(n, 0.0f);
    grad_gate.assign(n, 0.0f);
    policy_mix.assign(n * 2 * arch.action_width(), 0.0f);
  } else {
    gate_value.clear();
  }
}

void ForwardFeatures(const Architecture& arch, const float* params, ModelBuffers& buffers) {
  if (arch.image()) {
    ConvStackForward(arch.convs, params, buffers.y.data(), buffers.convs);
    const float* cnn_features = buffers.convs.output();
    if (arch.spatial_softmax) {
      SpatialSoftmaxForward(arch.keypoints, params, cnn_features, buffers.keypoints);
      cnn_features = buffers.keypoints.output();
    }
    MlpForward(arch.feature, params, cnn_features, buffers.feature);
    return;
  }
  const int x_dim = arch.spec.x_dim;
  const int y_dim = static_cast<int>(arch.spec.YSize());
  for (int b = 0; b < buffers.batch; ++b) {
    float* row = buffers.mlp_input.data() + static_cast<size_t>(b) * (x_dim + y_dim);
    std::copy_n(buffers.x.data() + static_cast<size_t>(b) * x_dim, x_dim, row);
    std::copy_n(buffers.y[b], y_dim, row + x_dim);
  }
  MlpForward(arch.feature, params, buffers.mlp_input.data(), buffers.feature);
}

void ForwardPolicy(const Architecture& arch, const float* params, ModelBuffers& buffers,
                   const float* phi_offsets) {
  const int x_dim = arch.spec.x_dim, k = arch.feature_dim();
  for (int b = 0; b < buffers.batch; ++b) {
    float* row = buffers.policy_input.data() + static_cast<size_t>(b) * (x_dim + k);
    std::copy_n(buffers.x.data() + static_cast<size_t>(b) * x_dim, x_dim, row);
    std::copy_n(buffers.phi() + static_cast<size_t>(b) * k, k, row + x_dim);
    if (phi_offsets == nullptr) continue;
    const float* offsets = phi_offsets + static_cast<size_t>(b) * k;
    for (int i = 0; i < k; ++i) row[x_dim + i] += offsets[i];
  }
  MlpForward(arch.policy, params, buffers.policy_input.data(), buffers.policy);
  if (!arch.has_gate()) return;
  MlpForward(arch.gate, params, buffers.x.data(), buffers.gate);
  const float* z = buffers.gate.output();
  for (int b = 0; b < buffers.batch; ++b) {
    buffers.gate_value[b] = 1.0f / (1.0f + std::exp(-z[b]));
    float* row = buffers.blind_input.data() + static_cast<size_t>(b) * (x_dim + k);
    std::copy_n(buffers.x.data() + static_cast<size_t>(b) * x_dim, x_dim, row);
  }
  MlpForward(arch.policy, params, buffers.blind_input.data(), buffers.policy_blind);
  const int head = 2 * arch.action_width();
  const float* seeing = buffers.policy.output();
  const float* blind = buffers.policy_blind.output();
  for (int b = 0; b < buffers.batch; ++b) {
    const float g = buffers.gate_value[b];
    for (int j = 0; j < head; ++j) {
      const size_t at = static_cast<size_t>(b) * head + j;
      buffers.policy_mix[at] = g * seeing[at] + (1.0f - g) * blind[at];
    }
  }
}

void ForwardBeacon(const Architecture& arch, const float* params, ModelBuffers& buffers) {
  MlpForward(arch.beacon, params, buffers.phi(), buffers.beacon);
}

void Backward(const Architecture& arch, const float* params, const float* grad_policy_head,
              const float* grad_beacon_head, ModelBuffers& buffers, float* grads,
              const float* grad_blind_head, const float* grad_phi_extra, float* grad_images) {
  const int x_dim = arch.spec.x_dim, k = arch.feature_dim();
  if (grad_phi_extra != nullptr) {
    std::copy_n(grad_phi_extra, buffers.grad_phi.size(), buffers.grad_phi.begin());
  } else {
    std::fill(buffers.grad_phi.begin(), buffers.grad_phi.end(), 0.0f);
  }
  if (grad_policy_head != nullptr) {
    MlpBackward(arch.policy, params, buffers.policy_input.data(), grad_policy_head, buffers.policy,
                grads, buffers.grad_policy_input.data());
    for (int b = 0; b < buffers.batch; ++b) {
      const float* row =
          buffers.grad_policy_input.data() + static_cast<size_t>(b) * (x_dim + k) + x_dim;
      float* out = buffers.grad_phi.data() + static_cast<size_t>(b) * k;
      for (int i = 0; i < k; ++i) out[i] += row[i];
    }
    if (arch.has_gate()) {
      if (grad_blind_head != nullptr) {
        MlpBackward(arch.policy, params, buffers.blind_input.data(), grad_blind_head,
                    buffers.policy_blind, grads, nullptr);
      }
      MlpBackward(arch.gate, params, buffers.x.data(), buffers.grad_gate.data(), buffers.gate,
                  grads, nullptr);
    }
  }
  if (grad_beacon_head != nullptr) {
    MlpBackward(arch.beacon, params, buffers.phi(), grad_beacon_head, buffers.beacon, grads,
                buffers.grad_beacon_input.data());
    for (size_t i = 0; i < buffers.grad_phi.size(); ++i) {
      buffers.grad_phi[i] += buffers.grad_beacon_input[i];
    }
  }
  if (arch.image() && arch.spatial_softmax) {
    MlpBackward(arch.feature, params, buffers.keypoints.output(), buffers.grad_phi.data(),
                buffers.feature, grads, buffers.keypoints.grad_output());
    SpatialSoftmaxBackward(arch.keypoints, params, buffers.convs.output(), buffers.keypoints, grads,
                           buffers.convs.grad_output());
    ConvStackBackward(arch.convs, params, buffers.y.data(), buffers.convs, grads, grad_images);
  } else if (arch.image()) {
    MlpBackward(arch.feature, params, buffers.convs.output(), buffers.grad_phi.data(),
                buffers.feature, grads, buffers.convs.grad_output());
    ConvStackBackward(arch.convs, params, buffers.y.data(), buffers.convs, grads, grad_images);
  } else {
    MlpBackward(arch.feature, params, buffers.mlp_input.data(), buffers.grad_phi.data(),
                buffers.feature, grads, nullptr);
  }
}

}  // namespace recon::learn
