// The Torch backend's step: the networks of architecture.h written with LibTorch operators, in
// the same order as our kernels (conv, 2x2 max-pool, ReLU; linear layers with their
// activations), scored with the same loss formulas and reductions as losses.cc, differentiated
// by autograd.
//
// Every weight and bias is its own leaf tensor over the trainer's flat buffer (from_blob, no
// copy), and its gradient is a tensor over the matching span of the trainer's gradient buffer,
// so autograd accumulates straight into it. The alternatives are slower on the benchmark step
// (authors' CNN, 3x32x32, batch 20; medians of 3x5 runs): 2.25 ms this way, 2.75 ms with
// narrow() views of one flat leaf (autograd scatters each layer's gradient into a zero tensor
// of all num_params floats and sums those), 2.7-3.0 ms with one persistent leaf that the
// weights are copied into and the gradient out of.

#include "engine/learn/torch/torch_step_impl.h"

#include <ATen/ATen.h>
#include <c10/core/GradMode.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "engine/learn/play_consistency.h"

namespace recon::learn {

namespace {

constexpr double kLog2Pi = 1.8378770664093453;  // log(2 pi), as in losses.cc

// A tensor over memory the trainer owns; never written through (inputs, targets, noise).
at::Tensor Wrap(const float* data, std::vector<int64_t> shape) {
  return at::from_blob(const_cast<float*>(data), shape, at::kFloat);
}

// Each sample's loss of a [batch][mean | logvar] head, as in losses.cc with a batch of one:
// the NLL summed over dimensions, the MSE of a sample averaged over them.
at::Tensor SampleLoss(LossKind kind, const at::Tensor& head, const at::Tensor& target,
                      const float* noise, const at::Tensor& min_logvar) {
  const int64_t d = target.size(1);
  const at::Tensor mean = head.narrow(1, 0, d);
  at::Tensor logvar = head.narrow(1, d, d);
  if (kind == LossKind::kNll) {
    // TrainConfig::nll_min_std, action_min_std: held at the floor (one per dimension), with no
    // gradient below it.
    if (min_logvar.defined()) logvar = at::maximum(logvar, min_logvar);
    const at::Tensor sq = (target - mean).square() * at::exp(-logvar);
    return (0.5 * ((logvar + kLog2Pi) + sq)).sum(1);
  }
  const at::Tensor sample = mean + at::exp(0.5 * logvar) * Wrap(noise, {target.size(0), d});
  return (sample - target).square().mean(1);
}

// The batch's mean of SampleLoss, as losses.cc.
at::Tensor HeadLoss(LossKind kind, const at::Tensor& head, const at::Tensor& target,
                    const float* noise, const at::Tensor& min_logvar) {
  return SampleLoss(kind, head, target, noise, min_logvar).mean();
}

// Per-dimension floors as a tensor, or an undefined one where no dimension has a floor.
at::Tensor Floors(const std::vector<float>& min_logvar) {
  const bool any =
      std::any_of(min_logvar.begin(), min_logvar.end(), [](float v) { return std::isfinite(v); });
  if (!any) return {};
  return Wrap(min_logvar.data(), {static_cast<int64_t>(min_logvar.size())}).clone();
}

// What a step keeps between Forward and Backward, and the tensors made once.
struct StepState {
  Architecture arch;
  TrainConfig train;
  int64_t y_size = 0;
  at::Tensor demo_y, play_y;    ///< the batch's y rows gathered (the trainer holds pointers)
  at::Tensor x_coord, y_coord;  ///< spatial softmax only: [h * w] coordinates of each position
  /// The NLL's log-variance floors per dimension (Floors): the policy head's, the beacon net's.
  at::Tensor policy_min_logvar, beacon_min_logvar;

  // Per step: the parameter leaves in layout order, and the weighted loss to differentiate.
  std::vector<at::Tensor> leaves;
  std::vector<int64_t> leaf_offsets;
  at::Tensor total;

  at::Tensor Leaf(const float* params, int64_t offset, std::vector<int64_t> shape) {
    at::Tensor t = Wrap(params + offset, std::move(shape)).requires_grad_(true);
    leaves.push_back(t);
    leaf_offsets.push_back(offset);
    return t;
  }

  at::Tensor Mlp(const std::vector<LinearLayer>& layers, const float* params, at::Tensor h) {
    for (const LinearLayer& l : layers) {
      h = at::linear(h, Leaf(params, l.weight, {l.out, l.in}), Leaf(params, l.bias, {l.out}));
      if (l.activation == Activation::kRelu) h = at::relu(h);
      if (l.activation == Activation::kTanh) h = at::tanh(h);
    }
    return h;
  }

  at::Tensor GatherY(const ModelBuffers& buffers, at::Tensor& rows) {
    float* out = rows.data_ptr<float>();
    for (int b = 0; b < buffers.batch; ++b) {
      std::copy_n(buffers.y[b], y_size, out + b * y_size);
    }
    return rows;
  }

  // The feature net on one batch. Each call makes fresh leaves, so a parameter used by the demo
  // and the play batch is two leaves over the same floats; their gradients add up in `grads`.
  at::Tensor Features(const float* params, const ModelBuffers& buffers, at::Tensor& y_rows) {
    const at::Tensor x = Wrap(buffers.x.data(), {buffers.batch, arch.spec.x_dim});
    const at::Tensor y = GatherY(buffers, y_rows);
    if (!arch.image()) return Mlp(arch.feature, params, at::cat({x, y}, 1));
    at::Tensor h = y;
    for (const ConvLayer& c : arch.convs) {
      h = at::conv2d(h, Leaf(params, c.weight, {c.out_channels, c.in_channels, c.kernel, c.kernel}),
                     Leaf(params, c.bias, {c.out_channels}));
      h = at::relu(at::max_pool2d(h, {2, 2}));  // our kernels' order (pool_relu_forward)
    }
    if (!arch.spatial_softmax) return Mlp(arch.feature, params, h.flatten(1));
    // As spatial_softmax.cc: logits f * (1 / T), softmax per plane, expected coordinates,
    // interleaved per channel as [x_0, y_0, x_1, y_1, ...].
    const at::Tensor log_t = Leaf(params, arch.keypoints.log_temperature, {1});
    const at::Tensor s = at::softmax(h.flatten(2) * at::exp(-log_t), 2);
    const at::Tensor keypoints = at::stack({(s * x_coord).sum(2), (s * y_coord).sum(2)}, 2);
    return Mlp(arch.feature, params, keypoints.flatten(1));
  }
};

class TorchStepImpl final : public TorchStep {
 public:
  explicit TorchStepImpl(const TorchStepSetup& setup);
  void Forward(const float* params, const TorchBatch& batch, StepMetrics& metrics) override;
  void Backward(float* grads) override;

 private:
  StepState s_;
};

TorchStepImpl::TorchStepImpl(const TorchStepSetup& setup) {
  const Architecture& arch = setup.arch;
  s_.arch = arch;
  s_.train = setup.train;
  s_.y_size = setup.y_size;
  std::vector<int64_t> shape = arch.spec.y_shape;
  shape.insert(shape.begin(), setup.train.batch_size);
  s_.demo_y = at::empty(shape, at::kFloat);
  s_.play_y = at::empty(shape, at::kFloat);
  s_.policy_min_logvar = Floors(setup.policy_min_logvar);
  s_.beacon_min_logvar = Floors(setup.beacon_min_logvar);
  if (arch.spatial_softmax) {
    const SpatialSoftmaxLayer& k = arch.keypoints;
    const std::vector<float>& xs = setup.keypoint_x;
    const std::vector<float>& ys = setup.keypoint_y;
    // Row-major planes: position r * w + c has x = xs[c], y = ys[r].
    std::vector<float> x_at, y_at;
    for (int r = 0; r < k.h; ++r) {
      for (int c = 0; c < k.w; ++c) {
        x_at.push_back(xs[c]);
        y_at.push_back(ys[r]);
      }
    }
    s_.x_coord = Wrap(x_at.data(), {k.h * k.w}).clone();
    s_.y_coord = Wrap(y_at.data(), {k.h * k.w}).clone();
  }
}

void TorchStepImpl::Forward(const float* params, const TorchBatch& batch, StepMetrics& metrics) {
  StepState& s = s_;
  // Gradients are wanted even if a caller up the stack turned them off for inference.
  const c10::AutoGradMode grad_mode(true);
  s.leaves.clear();
  s.leaf_offsets.clear();
  const DataSpec& spec = s.arch.spec;
  const int64_t n = batch.demo->batch;
  const LossKind kind = s.train.loss;

  const at::Tensor x = Wrap(batch.demo->x.data(), {n, spec.x_dim});
  const at::Tensor phi = s.Features(params, *batch.demo, s.demo_y);
  at::Tensor policy_phi = phi;
  if (batch.feature_noise != nullptr) {  // as FeatureNoiseOffsets: the spread held constant
    const at::Tensor spread = phi.detach().std(0, /*unbiased=*/false);
    policy_phi = phi + (s.train.feature_noise * spread) *
                           Wrap(batch.feature_noise, {n, s.arch.feature_dim()});
  }
  // Per action of the chunk, as the fused backend does (trainer.cc).
  const at::Tensor target_u = Wrap(batch.target_u, {n, s.arch.action_width()});
  const at::Tensor seeing = s.Mlp(s.arch.policy, params, at::cat({x, policy_phi}, 1));
  const double chunk = static_cast<double>(s.arch.network.action_chunk);
  const at::Tensor seeing_loss =
      SampleLoss(kind, seeing, target_u, batch.noise_u, s.policy_min_logvar);
  // Fixed gate targets route each sample to one branch (GatedActionLoss, trainer_step.cc).
  const bool routed = s.arch.has_gate() && batch.gate_target != nullptr;
  const at::Tensor route = routed ? Wrap(batch.gate_target, {n}) : at::ones({n});
  const at::Tensor action = (route * seeing_loss).mean() / chunk;
  at::Tensor total = action * s.train.action_weight;
  metrics.action_loss = action.item<float>();
  if (s.arch.has_gate()) {
    // As GatedActionLoss (trainer_step.cc): the blind branch (on every sample, or where the
    // route says), and the gate's cross-entropy against its targets.
    const at::Tensor logit = s.Mlp(s.arch.gate, params, x).squeeze(1);
    const at::Tensor blind =
        s.Mlp(s.arch.policy, params, at::cat({x, at::zeros_like(policy_phi)}, 1));
    const at::Tensor blind_route = routed ? 1.0f - route : at::ones({n});
    const at::Tensor blind_loss =
        blind_route * SampleLoss(kind, blind, target_u, batch.noise_u, s.policy_min_logvar);
    const at::Tensor target =
        routed ? route
               : ((blind_loss - seeing_loss).detach() / chunk > s.train.gate_margin).to(at::kFloat);
    const at::Tensor gate_loss = at::binary_cross_entropy_with_logits(logit, target);
    const at::Tensor blind_action = blind_loss.mean() / chunk;
    total = total + blind_action * s.train.action_weight + gate_loss;
    metrics.blind_loss = blind_action.item<float>();
    metrics.gate_loss = gate_loss.item<float>();
    metrics.gate_mean = at::sigmoid(logit).mean().item<float>();
  }
  if (s.arch.has_beacon_net()) {
    const at::Tensor beacon =
        HeadLoss(kind, s.Mlp(s.arch.beacon, params, phi), Wrap(batch.target_b, {n, spec.b_dim}),
                 batch.noise_b, s.beacon_min_logvar);
    total = total + beacon * s.train.beacon_weight;
    metrics.beacon_loss = beacon.item<float>();
  }
  if (batch.play != nullptr) {
    const at::Tensor play_phi = s.Features(params, *batch.play, s.play_y);
    const at::Tensor play =
        HeadLoss(kind, s.Mlp(s.arch.beacon, params, play_phi),
                 Wrap(batch.target_play, {n, spec.b_dim}), batch.noise_play, s.beacon_min_logvar);
    total = total + play * s.train.play_weight;
    metrics.play_loss = play.item<float>();
    const int64_t pairs = n / 2;
    if (s.train.play_consistency > 0 && pairs > 0) {
      // As PlayConsistencyLoss: rows 2p and 2p + 1 are pair p; the total variance is
      // differentiated too.
      const at::Tensor centred = play_phi - play_phi.mean(0, /*keepdim=*/true);
      const at::Tensor spread = 2 * centred.pow(2).sum(1).mean() + kPlayConsistencySpreadFloor;
      const at::Tensor first = play_phi.slice(0, 0, 2 * pairs, 2);
      const at::Tensor second = play_phi.slice(0, 1, 2 * pairs, 2);
      const at::Tensor consistency = (first - second).pow(2).sum(1).mean() / spread;
      total = total + consistency * s.train.play_consistency;
      metrics.consistency_loss = consistency.item<float>();
    }
  }
  s.total = total;
}

void TorchStepImpl::Backward(float* grads) {
  StepState& s = s_;
  if (!s.total.defined()) throw std::logic_error("TorchStep::Backward without Forward");
  // A defined .grad is accumulated into in place (AccumulateGrad), i.e. straight into `grads`.
  for (size_t i = 0; i < s.leaves.size(); ++i) {
    s.leaves[i].mutable_grad() = Wrap(grads + s.leaf_offsets[i], s.leaves[i].sizes().vec());
  }
  s.total.backward();
  for (size_t i = 0; i < s.leaves.size(); ++i) {
    if (s.leaves[i].grad().data_ptr<float>() != grads + s.leaf_offsets[i]) {
      throw std::logic_error("Torch backend: autograd replaced a gradient buffer");
    }
  }
  // Drop the graph and the wrappers now: they point into the trainer's buffers.
  s.total.reset();
  s.leaves.clear();
  s.leaf_offsets.clear();
}

}  // namespace

std::unique_ptr<TorchStep> NewTorchStep(const TorchStepSetup& setup) {
  return std::make_unique<TorchStepImpl>(setup);
}

}  // namespace recon::learn
