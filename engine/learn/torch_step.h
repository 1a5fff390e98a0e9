#pragma once

// The Torch backend (Backend::kTorch): one training step's forward pass, losses and backward pass
// written with LibTorch operators and autograd, over the trainer's own flat parameters. Only the
// gradient comes from here: the batch, the noise, the divergence checks and the Adam update stay
// the trainer's, so both backends train the same model from the same state. Internal; does not
// include Torch (torch_step.cc is the only file that pays its compile cost).

#include <memory>

#include "engine/learn/architecture.h"
#include "engine/learn/learner.h"
#include "engine/learn/model.h"

namespace recon::learn {

/// One step's batch as the trainer gathered it. `x` and `y` of the buffers are read (y already
/// multiplied by image_scale); rows are [batch][dim]. Noise is read only for kMseSample.
struct TorchBatch {
  const ModelBuffers* demo = nullptr;
  const ModelBuffers* play = nullptr;  ///< null when the play term is off
  const float* target_u = nullptr;
  const float* target_b = nullptr;  ///< null without a beacon net
  const float* target_play = nullptr;
  const float* noise_u = nullptr;
  const float* noise_b = nullptr;
  const float* noise_play = nullptr;
  const float* feature_noise = nullptr;  ///< [batch][k] draws; null when feature noise is off
  /// [batch] fixed gate targets (GateTarget::kDisagreement); null = targets from the losses
  const float* gate_target = nullptr;
};

class TorchStep {
 public:
  TorchStep(const Architecture& arch, const TrainConfig& train);
  ~TorchStep();
  TorchStep(const TorchStep&) = delete;
  TorchStep& operator=(const TorchStep&) = delete;

  /// Runs the forward pass on `params` (num_params floats, not copied: they must stay in place
  /// until Backward) and writes the unweighted per-term losses into `metrics`.
  void Forward(const float* params, const TorchBatch& batch, StepMetrics& metrics);
  /// Backpropagates the weighted sum of the last Forward's losses and adds dLoss/dparams to
  /// `grads` (num_params floats, laid out like params).
  void Backward(float* grads);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace recon::learn
