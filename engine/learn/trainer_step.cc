// The backend-specific half of a training step (TrainerImpl::Step): the forward pass and losses
// on our own kernels and their backward pass, or the batch handed to the Torch backend.

#include <algorithm>
#include <cmath>

#include "engine/learn/augmentation.h"
#include "engine/learn/losses.h"
#include "engine/learn/trainer_impl.h"

namespace recon::learn {

void TrainerImpl::FusedForward(StepMetrics& m) {
  const float* params = params_.data();
  const int batch = train_.batch_size;
  const DataSpec& s = data_.spec;
  ForwardFeatures(arch_, params, demo_);
  const bool noisy = train_.feature_noise > 0;
  if (noisy) {
    FeatureNoiseOffsets(demo_.phi(), batch, arch_.feature_dim(), train_.feature_noise,
                        feature_noise_.data(), phi_offsets_.data());
  }
  ForwardPolicy(arch_, params, demo_, noisy ? phi_offsets_.data() : nullptr);
  // With a chunk of k actions the head's loss sums k actions' terms: per action (divided by k)
  // it weighs against the beacon term as a single action does.
  const float chunk = static_cast<float>(network_.action_chunk);
  if (arch_.has_gate()) {
    m.action_loss = GatedActionLoss(m) / chunk;
  } else {
    m.action_loss =
        HeadLoss(train_.loss, demo_.policy_head(), target_u_.data(), noise_u_.data(), batch,
                 arch_.action_width(), static_cast<float>(train_.action_weight) / chunk,
                 grad_policy_head_.data(), policy_min_logvar_.data()) /
        chunk;
  }
  if (arch_.has_beacon_net()) {
    ForwardBeacon(arch_, params, demo_);
    m.beacon_loss = HeadLoss(train_.loss, demo_.beacon_head(), target_b_.data(), noise_b_.data(),
                             batch, s.b_dim, static_cast<float>(train_.beacon_weight),
                             grad_beacon_head_.data(), beacon_min_logvar_.data());
  }
  if (UsesPlay()) {
    ForwardFeatures(arch_, params, play_);
    ForwardBeacon(arch_, params, play_);
    m.play_loss = HeadLoss(
        train_.loss, play_.beacon_head(), target_play_.data(), noise_play_.data(), batch, s.b_dim,
        static_cast<float>(train_.play_weight), grad_play_head_.data(), beacon_min_logvar_.data());
    if (UsesPlayConsistency()) {
      m.consistency_loss =
          PlayConsistencyLoss(play_.phi(), batch, arch_.feature_dim(),
                              static_cast<float>(train_.play_consistency), grad_play_phi_.data());
    }
  }
}

// The feature gate's terms (NetworkConfig::feature_gate_hidden): both branches' action losses on
// every sample, and the gate's cross-entropy against its targets (GateTarget): "seeing lowers
// this sample's loss by more than gate_margin per action", or the rows' fixed disagreement ones.
// Returns the seeing branch's action term; the blind branch's and the gate's go to `m`.
float TrainerImpl::GatedActionLoss(StepMetrics& m) {
  const int batch = train_.batch_size, width = arch_.action_width();
  const float chunk = static_cast<float>(network_.action_chunk);
  const float weight = static_cast<float>(train_.action_weight) / chunk / static_cast<float>(batch);
  const float* z = demo_.gate.output();
  double seeing_sum = 0, blind_sum = 0, gate_loss = 0, gate_sum = 0;
  // Fixed targets (GateTarget::kDisagreement) also route each sample's action loss to the branch
  // its target picks, as if the features were masked wherever the gate should shut: a seeing
  // branch trained on every sample learns to read the features where they only help memorise.
  const bool routed = !batch_gate_targets_.empty();
  for (int b = 0; b < batch; ++b) {
    const size_t head = static_cast<size_t>(b) * 2 * width, row = static_cast<size_t>(b) * width;
    const float route = routed ? batch_gate_targets_[b] : 1.0f;
    const float seeing = HeadLoss(train_.loss, demo_.seeing_head() + head, target_u_.data() + row,
                                  noise_u_.data() + row, 1, width, weight * route,
                                  grad_policy_head_.data() + head, policy_min_logvar_.data());
    const float blind_route = routed ? 1.0f - route : 1.0f;
    const float blind = HeadLoss(train_.loss, demo_.blind_head() + head, target_u_.data() + row,
                                 noise_u_.data() + row, 1, width, weight * blind_route,
                                 grad_blind_head_.data() + head, policy_min_logvar_.data());
    seeing_sum += route * seeing;
    blind_sum += blind_route * blind;
    const float target =
        routed ? route : ((blind - seeing) / chunk > train_.gate_margin ? 1.0f : 0.0f);
    // Cross-entropy from the logit z: softplus(z) - t z, whose slope is sigmoid(z) - t.
    const double zb = z[b];
    gate_loss += std::max(zb, 0.0) + std::log1p(std::exp(-std::abs(zb))) - target * zb;
    demo_.grad_gate[b] = (demo_.gate_value[b] - target) / static_cast<float>(batch);
    gate_sum += demo_.gate_value[b];
  }
  m.gate_mean = static_cast<float>(gate_sum / batch);
  m.gate_loss = static_cast<float>(gate_loss / batch);
  m.blind_loss = static_cast<float>(blind_sum / batch / chunk);
  return static_cast<float>(seeing_sum / batch);
}

void TrainerImpl::FusedBackward() {
  const float* params = params_.data();
  Backward(arch_, params, grad_policy_head_.data(),
           arch_.has_beacon_net() ? grad_beacon_head_.data() : nullptr, demo_, grads_.data(),
           arch_.has_gate() ? grad_blind_head_.data() : nullptr);
  if (UsesPlay()) {
    Backward(arch_, params, nullptr, grad_play_head_.data(), play_, grads_.data(), nullptr,
             UsesPlayConsistency() ? grad_play_phi_.data() : nullptr);
  }
}

TorchBatch TrainerImpl::MakeTorchBatch() const {
  TorchBatch b;
  b.demo = &demo_;
  b.play = UsesPlay() ? &play_ : nullptr;
  b.target_u = target_u_.data();
  b.target_b = target_b_.data();
  b.target_play = target_play_.data();
  b.noise_u = noise_u_.data();
  b.noise_b = noise_b_.data();
  b.noise_play = noise_play_.data();
  b.feature_noise = train_.feature_noise > 0 ? feature_noise_.data() : nullptr;
  b.gate_target = batch_gate_targets_.empty() ? nullptr : batch_gate_targets_.data();
  return b;
}

}  // namespace recon::learn
