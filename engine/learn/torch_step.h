#pragma once

// The Torch backend (Backend::kTorch): one training step's forward pass, losses and backward pass
// written with LibTorch operators and autograd, over the trainer's own flat parameters. Only the
// gradient comes from here: the batch, the noise, the divergence checks and the Adam update stay
// the trainer's, so both backends train the same model from the same state. Internal; does not
// include Torch: the step itself lives in the Torch module (torch_module.h), loaded on first use.

#include <memory>
#include <vector>

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

/// What the module's step needs beyond the architecture and the recipe, computed here so that
/// the module calls nothing of the learner's (it links LibTorch only).
struct TorchStepSetup {
  Architecture arch;
  TrainConfig train;
  int64_t y_size = 0;                         ///< arch.spec.YSize()
  std::vector<float> policy_min_logvar;       ///< TrainConfig::PolicyMinLogVar per dimension
  std::vector<float> beacon_min_logvar;       ///< TrainConfig::NllMinLogVar per dimension
  std::vector<float> keypoint_x, keypoint_y;  ///< KeypointCoordinates(w), (h); spatial softmax
};

class TorchStep {
 public:
  virtual ~TorchStep() = default;
  /// Runs the forward pass on `params` (num_params floats, not copied: they must stay in place
  /// until Backward) and writes the unweighted per-term losses into `metrics`.
  virtual void Forward(const float* params, const TorchBatch& batch, StepMetrics& metrics) = 0;
  /// Backpropagates the weighted sum of the last Forward's losses and adds dLoss/dparams to
  /// `grads` (num_params floats, laid out like params).
  virtual void Backward(float* grads) = 0;
};

/// The Torch backend's step for `arch` trained with `train` (loads the Torch module).
std::unique_ptr<TorchStep> MakeTorchStep(const Architecture& arch, const TrainConfig& train);

}  // namespace recon::learn
