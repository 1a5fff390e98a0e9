#pragma once

// The trainer's state and one training step. Internal: trainer.cc drives it (the step's backend
// half is in trainer_step.cc), checkpoint.cc saves and restores it.

#include <functional>
#include <memory>
#include <vector>

#include "engine/core/rng.h"
#include "engine/learn/aligned_buffer.h"
#include "engine/learn/architecture.h"
#include "engine/learn/learner.h"
#include "engine/learn/model.h"
#include "engine/learn/play_consistency.h"
#include "engine/learn/target_scaling.h"
#include "engine/learn/torch_step.h"
#include "engine/learn/training_data.h"

namespace recon::learn {

/// Everything that determines how training continues. A checkpoint stores exactly this (plus the
/// configurations), which is why a resumed run is bitwise identical to an uninterrupted one.
struct TrainerState {
  int attempt = 0;
  int step = 0;           ///< steps done in this attempt
  bool finished = false;  ///< the last attempt completed and the restart rule accepted it
  int64_t adam_step = 0;
  Rng::State batch_rng{};
  Rng::State noise_rng{};
  Rng::State augment_rng{};  ///< image shifts and feature noise (TrainConfig)
  StepMetrics last;
  std::vector<float> params, exp_avg, exp_avg_sq;
};

/// Mean squared errors of the heads' mean predictions over the whole training set (the restart
/// rule's measure). beacon_and_play is 0 for the Baseline.
struct TrainingErrors {
  double action = 0;
  double beacon_and_play = 0;
};

class TrainerImpl {
 public:
  /// Checks the setup (UserError) and starts attempt 0.
  TrainerImpl(const Dataset& data, const NetworkConfig& network, const TrainConfig& train);

  TrainResult Train(const std::atomic<bool>* cancel);
  /// One step of the current attempt. DivergenceError if the loss or a gradient is not finite;
  /// then nothing has changed.
  void Step();
  TrainingErrors Evaluate();

  TrainerState State() const;
  /// UserError if the state does not fit this trainer's architecture.
  void SetState(const TrainerState& state);

  std::shared_ptr<PolicyImpl> MakePolicy() const;

  const NetworkConfig& network() const { return network_; }
  const TrainConfig& train() const { return train_; }
  const Architecture& arch() const { return arch_; }
  uint64_t fingerprint() const { return data_.fingerprint; }
  const TargetScaling& scaling() const { return scaling_; }
  int step() const { return step_; }
  void set_observer(std::function<void(const StepMetrics&)> observer) {
    observer_ = std::move(observer);
  }

 private:
  void StartAttempt(int attempt);
  bool UsesPlay() const;
  bool UsesPlayConsistency() const;  ///< TrainConfig::play_consistency, with play data
  bool NeedsRestart();
  void GatherBatch();
  // The backend-specific half of Step (trainer_step.cc): the unweighted losses into `m`, then
  // dLoss/dparams added into grads_ (zeroed by the caller).
  void FusedForward(StepMetrics& m);
  void FusedBackward();
  float GatedActionLoss(StepMetrics& m);
  TorchBatch MakeTorchBatch() const;

  NetworkConfig network_;
  TrainConfig train_;
  Architecture arch_;
  TrainingData data_;  ///< targets in standardised units when train_.standardize_targets
  TargetScaling scaling_;
  std::function<void(const StepMetrics&)> observer_;

  int attempt_ = 0;
  int step_ = 0;
  bool finished_ = false;
  int64_t adam_step_ = 0;
  Rng batch_rng_{0};
  Rng noise_rng_{0};
  Rng augment_rng_{0};
  StepMetrics last_;
  AlignedFloats params_, grads_, exp_avg_, exp_avg_sq_;
  std::vector<ParamRange> decayed_;  ///< TrainConfig::weight_decay's weights; empty without it

  // Per-step scratch, allocated once.
  ModelBuffers demo_, play_, eval_;
  std::vector<float> target_u_, target_b_, target_play_;
  std::vector<float> noise_u_, noise_b_, noise_play_;
  std::vector<float> grad_policy_head_, grad_beacon_head_, grad_play_head_;
  /// The NLL's log-variance floors per dimension of the policy and beacon heads' means
  /// (TrainConfig::PolicyMinLogVar, NllMinLogVar).
  std::vector<float> policy_min_logvar_, beacon_min_logvar_;
  std::vector<float> feature_noise_, phi_offsets_;  ///< TrainConfig::feature_noise draws, offsets
  std::vector<float> grad_blind_head_;              ///< the feature gate's blind branch
  /// TrainConfig::play_consistency (UsesPlayConsistency): each play row's chunk, and the term's
  /// gradient on the play batch's features. Empty when it is off.
  PlayChunks play_chunks_;
  std::vector<float> grad_play_phi_;
  /// GateTarget::kDisagreement: each demonstration row's gate target (fixed before training),
  /// and the batch's. Empty otherwise.
  std::vector<float> row_gate_targets_, batch_gate_targets_;
  AlignedFloats shifted_demo_y_, shifted_play_y_;  ///< the batch's augmented images
  std::unique_ptr<TorchStep> torch_;               ///< Backend::kTorch only
};

}  // namespace recon::learn
