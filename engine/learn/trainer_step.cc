// The backend-specific half of a training step (TrainerImpl::Step): the forward pass and losses
// on our own kernels and their backward pass, or the batch handed to the Torch backend.

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
                 grad_policy_head_.data()) /
        chunk;
  }
  if (arch_.has_beacon_net()) {
    ForwardBeacon(arch_, params, demo_);
    m.beacon_loss =
        HeadLoss(train_.loss, demo_.beacon_head(), target_b_.data(), noise_b_.data(), batch,
                 s.b_dim, static_cast<float>(train_.beacon_weight), grad_beacon_head_.data());
  }
  if (UsesPlay()) {
    ForwardFeatures(arch_, params, play_);
    ForwardBeacon(arch_, params, play_);
    m.play_loss =
        HeadLoss(train_.loss, play_.beacon_head(), target_play_.data(), noise_play_.data(), batch,
                 s.b_dim, static_cast<float>(train_.play_weight), grad_play_head_.data());
  }
}

// The feature gate's action term: per sample, the seeing branch's loss with weight g and the
// blind branch's with weight 1 - g (the expected loss of a policy that looks at the features
// with probability g), so d/dg = L_seeing - L_blind + the penalty's slope: the gate shuts
// wherever the features lower the loss by less than gate_penalty.
float TrainerImpl::GatedActionLoss(StepMetrics& m) {
  const int batch = train_.batch_size, width = arch_.action_width();
  const float weight = static_cast<float>(train_.action_weight) /
                       static_cast<float>(network_.action_chunk) / static_cast<float>(batch);
  double loss = 0, gate_sum = 0;
  for (int b = 0; b < batch; ++b) {
    const float g = demo_.gate_value[b];
    const size_t head = static_cast<size_t>(b) * 2 * width, row = static_cast<size_t>(b) * width;
    const float seeing =
        HeadLoss(train_.loss, demo_.seeing_head() + head, target_u_.data() + row,
                 noise_u_.data() + row, 1, width, weight * g, grad_policy_head_.data() + head);
    const float blind = HeadLoss(train_.loss, demo_.blind_head() + head, target_u_.data() + row,
                                 noise_u_.data() + row, 1, width, weight * (1.0f - g),
                                 grad_blind_head_.data() + head);
    loss += g * seeing + (1.0f - g) * blind;
    gate_sum += g;
    demo_.grad_gate[b] = (weight * (seeing - blind) +
                          static_cast<float>(train_.gate_penalty) / static_cast<float>(batch)) *
                         g * (1.0f - g);
  }
  m.gate_mean = static_cast<float>(gate_sum / batch);
  return static_cast<float>(loss / batch);
}

void TrainerImpl::FusedBackward() {
  const float* params = params_.data();
  Backward(arch_, params, grad_policy_head_.data(),
           arch_.has_beacon_net() ? grad_beacon_head_.data() : nullptr, demo_, grads_.data(),
           arch_.has_gate() ? grad_blind_head_.data() : nullptr);
  if (UsesPlay()) {
    Backward(arch_, params, nullptr, grad_play_head_.data(), play_, grads_.data());
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
  return b;
}

}  // namespace recon::learn
