#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "engine/core/error.h"
#include "engine/learn/augmentation.h"
#include "engine/learn/beacon_filter.h"
#include "engine/learn/gate_targets.h"
#include "engine/learn/kernels.h"
#include "engine/learn/losses.h"
#include "engine/learn/policy_impl.h"
#include "engine/learn/setup_check.h"
#include "engine/learn/trainer_impl.h"

namespace recon::learn {

namespace {

// PyTorch's Adam defaults (the authors use them).
constexpr float kBeta1 = 0.9f, kBeta2 = 0.999f, kAdamEps = 1e-8f;
constexpr int kEvalChunk = 256;

// Independent streams of one attempt's seed: weights, batch indices, sampling noise.
enum Stream : uint64_t { kInitStream = 0, kBatchStream = 1, kNoiseStream = 2, kAugmentStream = 3 };

void FillNormal(Rng& rng, std::vector<float>& out) {
  for (float& v : out) v = static_cast<float>(rng.Normal());
}

template <typename T>
void CopyRow(const std::vector<T>& source, int64_t row, int width, T* dest) {
  std::copy_n(source.data() + row * width, width, dest);
}

}  // namespace

TrainerImpl::TrainerImpl(const Dataset& data, const NetworkConfig& network,
                         const TrainConfig& train)
    : network_(network), train_(train) {
  CheckTrainingSetup(data, network, train);
  arch_ = BuildArchitecture(data.spec, network, train.method);
  data_ = TrainingData::From(data, network.image_scale, network.action_chunk);
  // Which play rows were recorded together (Dataset::play_chunks), for the settings that use it.
  const std::vector<int32_t> play_groups = train.beacon_filter_samples > 0 || UsesPlayConsistency()
                                               ? GroupsOfChunks(data_.num_play, data.play_chunks)
                                               : std::vector<int32_t>{};
  if (train.beacon_filter_samples > 0) {
    const int d = data.spec.b_dim;
    SmoothBeaconRows(data_.demo_b, d, data_.demo_episode, train.beacon_filter_samples);
    SmoothBeaconRows(data_.play_b, d, play_groups, train.beacon_filter_samples);
  }
  scaling_ =
      train.standardize_targets ? TargetScaling::Fit(data_) : TargetScaling::Identity(data.spec);
  if (train.standardize_inputs) scaling_.FitInputs(data_);
  scaling_.Apply(data_);
  const size_t n = static_cast<size_t>(arch_.num_params);
  params_.assign(n, 0.0f);
  grads_.assign(n, 0.0f);
  exp_avg_.assign(n, 0.0f);
  exp_avg_sq_.assign(n, 0.0f);

  const int batch = train.batch_size;
  const DataSpec& s = data.spec;
  demo_.Resize(arch_, batch);
  target_u_.assign(static_cast<size_t>(batch) * arch_.action_width(), 0.0f);
  noise_u_.assign(target_u_.size(), 0.0f);
  grad_policy_head_.assign(2 * target_u_.size(), 0.0f);
  policy_min_logvar_ = train.PolicyMinLogVar(s.u_dim, network.action_chunk);
  beacon_min_logvar_.assign(static_cast<size_t>(s.b_dim), train.NllMinLogVar());
  if (arch_.has_beacon_net()) {
    target_b_.assign(static_cast<size_t>(batch) * s.b_dim, 0.0f);
    noise_b_.assign(target_b_.size(), 0.0f);
    grad_beacon_head_.assign(2 * target_b_.size(), 0.0f);
  }
  if (UsesPlay()) {
    play_.Resize(arch_, batch);
    target_play_.assign(target_b_.size(), 0.0f);
    noise_play_.assign(target_b_.size(), 0.0f);
    grad_play_head_.assign(grad_beacon_head_.size(), 0.0f);
    if (UsesPlayConsistency()) {
      play_chunks_ = PlayChunks::FromGroups(play_groups);
      grad_play_phi_.assign(static_cast<size_t>(batch) * arch_.feature_dim(), 0.0f);
    }
  }
  if (train.random_shift_px > 0 || train.random_erase_px > 0) {
    shifted_demo_y_.assign(static_cast<size_t>(batch) * data_.y_size, 0.0f);
    if (UsesPlay()) shifted_play_y_.assign(shifted_demo_y_.size(), 0.0f);
  }
  if (train.feature_noise > 0) {
    feature_noise_.assign(static_cast<size_t>(batch) * arch_.feature_dim(), 0.0f);
    phi_offsets_.assign(feature_noise_.size(), 0.0f);
  }
  if (arch_.has_gate()) {
    grad_blind_head_.assign(grad_policy_head_.size(), 0.0f);
    if (train.gate_target == GateTarget::kDisagreement) {
      row_gate_targets_ = DisagreementGateTargets(data_, scaling_.u_scale, train.gate_margin);
      batch_gate_targets_.assign(static_cast<size_t>(batch), 0.0f);
    }
  }
  if (train.weight_decay > 0) decayed_ = WeightRanges(arch_);
  if (train.backend == Backend::kTorch) torch_ = MakeTorchStep(arch_, train_);
  StartAttempt(0);
}

bool TrainerImpl::UsesPlay() const { return arch_.has_beacon_net() && data_.num_play > 0; }

bool TrainerImpl::UsesPlayConsistency() const { return UsesPlay() && train_.play_consistency > 0; }

void TrainerImpl::StartAttempt(int attempt) {
  attempt_ = attempt;
  step_ = 0;
  finished_ = false;
  adam_step_ = 0;
  last_ = StepMetrics{};
  last_.attempt = attempt;
  const uint64_t seed = Rng::Derive(train_.seed, static_cast<uint64_t>(attempt));
  Rng init(Rng::Derive(seed, kInitStream));
  InitializeParameters(arch_, init, params_.data());
  batch_rng_.Seed(Rng::Derive(seed, kBatchStream));
  noise_rng_.Seed(Rng::Derive(seed, kNoiseStream));
  augment_rng_.Seed(Rng::Derive(seed, kAugmentStream));
  std::fill(exp_avg_.begin(), exp_avg_.end(), 0.0f);
  std::fill(exp_avg_sq_.begin(), exp_avg_sq_.end(), 0.0f);
}

void TrainerImpl::GatherBatch() {
  const DataSpec& s = data_.spec;
  const bool beacons = arch_.has_beacon_net();
  for (int i = 0; i < demo_.batch; ++i) {
    const int64_t row = static_cast<int64_t>(batch_rng_.UniformInt(data_.num_demo));
    CopyRow(data_.demo_x, row, s.x_dim, demo_.x.data() + i * s.x_dim);
    CopyRow(data_.demo_u, row, arch_.action_width(), target_u_.data() + i * arch_.action_width());
    if (beacons) CopyRow(data_.demo_b, row, s.b_dim, target_b_.data() + i * s.b_dim);
    demo_.y[i] = data_.DemoY(row);
    if (!row_gate_targets_.empty()) batch_gate_targets_[i] = row_gate_targets_[row];
  }
  if (UsesPlay()) {
    const bool pairs = UsesPlayConsistency();
    int64_t row = 0;
    for (int i = 0; i < play_.batch; ++i) {
      // With play consistency, rows 2p and 2p + 1 come from one chunk (PlayConsistencyLoss).
      row = pairs && i % 2 == 1 ? play_chunks_.Partner(row, batch_rng_)
                                : static_cast<int64_t>(batch_rng_.UniformInt(data_.num_play));
      CopyRow(data_.play_x, row, s.x_dim, play_.x.data() + i * s.x_dim);
      CopyRow(data_.play_b, row, s.b_dim, target_play_.data() + i * s.b_dim);
      play_.y[i] = data_.PlayY(row);
    }
  }
  if (train_.random_shift_px > 0 || train_.random_erase_px > 0) {
    const int channels = static_cast<int>(s.y_shape[0]), height = static_cast<int>(s.y_shape[1]),
              width = static_cast<int>(s.y_shape[2]);
    // The image is copied into the batch's own buffer (shifted, or as it is), and erased there:
    // the dataset's images are never written.
    auto augment = [&](const float*& image, float* out) {
      if (train_.random_shift_px > 0) {
        const Shift d = DrawShift(augment_rng_, train_.random_shift_px);
        ShiftImage(image, channels, height, width, d.dy, d.dx, out);
      } else {
        std::copy(image, image + data_.y_size, out);
      }
      if (train_.random_erase_px > 0) {
        const Erase e = DrawErase(augment_rng_, height, width, train_.random_erase_px);
        EraseSquare(out, channels, height, width, e);
      }
      image = out;
    };
    for (int i = 0; i < demo_.batch; ++i) {
      augment(demo_.y[i], shifted_demo_y_.data() + i * data_.y_size);
    }
    if (UsesPlay()) {
      for (int i = 0; i < play_.batch; ++i) {
        augment(play_.y[i], shifted_play_y_.data() + i * data_.y_size);
      }
    }
  }
  if (train_.feature_noise > 0) FillNormal(augment_rng_, feature_noise_);
  if (train_.loss == LossKind::kMseSample) {
    FillNormal(noise_rng_, noise_u_);
    if (beacons) FillNormal(noise_rng_, noise_b_);
    if (UsesPlay()) FillNormal(noise_rng_, noise_play_);
  }
}

void TrainerImpl::Step() {
  // Everything that can fail is done before the first write to the trainer's state, so that a
  // DivergenceError leaves weights, optimizer and generators as they were before the step.
  const Rng::State batch_before = batch_rng_.GetState(), noise_before = noise_rng_.GetState();
  const Rng::State augment_before = augment_rng_.GetState();
  GatherBatch();
  StepMetrics m;
  m.attempt = attempt_;
  m.step = step_;
  // --- Backend: forward pass and losses (terms that are off stay 0) ---
  if (torch_ != nullptr) {
    torch_->Forward(params_.data(), MakeTorchBatch(), m);
  } else {
    FusedForward(m);
  }
  // --- end backend ---
  double total = train_.action_weight * m.action_loss;
  if (arch_.has_beacon_net()) total += train_.beacon_weight * m.beacon_loss;
  if (UsesPlay()) total += train_.play_weight * m.play_loss;
  if (UsesPlayConsistency()) total += train_.play_consistency * m.consistency_loss;
  if (arch_.has_gate()) total += train_.action_weight * m.blind_loss + m.gate_loss;
  m.total_loss = static_cast<float>(total);

  auto diverged = [&](const std::string& what) {
    batch_rng_.SetState(batch_before);
    noise_rng_.SetState(noise_before);
    augment_rng_.SetState(augment_before);
    std::ostringstream msg;
    msg << "training diverged at step " << step_ << " (attempt " << attempt_ << "): " << what
        << " (action loss " << m.action_loss << ", beacon " << m.beacon_loss << ", play "
        << m.play_loss << "); try a lower learning rate (now " << train_.learning_rate << ")";
    throw DivergenceError(msg.str(), step_);
  };
  if (!std::isfinite(m.total_loss)) diverged("the loss is not finite");

  std::fill(grads_.begin(), grads_.end(), 0.0f);
  // --- Backend: gradient of the weighted loss into grads_ ---
  if (torch_ != nullptr) {
    torch_->Backward(grads_.data());
  } else {
    FusedBackward();
  }
  // --- end backend ---
  const kernels::KernelTable& k = kernels::Kernels();
  if (!k.all_finite(grads_.data(), static_cast<int64_t>(grads_.size()))) {
    diverged("a gradient is not finite");
  }

  ++adam_step_;
  kernels::AdamArgs a;
  a.size = static_cast<int64_t>(params_.size());
  a.param = params_.data();
  a.grad = grads_.data();
  a.exp_avg = exp_avg_.data();
  a.exp_avg_sq = exp_avg_sq_.data();
  a.lr = static_cast<float>(
      ScheduledLearningRate(train_.learning_rate, train_.lr_schedule, step_, train_.steps));
  // Decoupled weight decay comes first, as PyTorch's AdamW applies it.
  ScaleRanges(decayed_, 1.0f - a.lr * static_cast<float>(train_.weight_decay), params_.data());
  a.beta1 = kBeta1;
  a.beta2 = kBeta2;
  a.eps = kAdamEps;
  const double t = static_cast<double>(adam_step_);
  a.bias_correction1 = static_cast<float>(1.0 - std::pow(static_cast<double>(kBeta1), t));
  a.bias_correction2_sqrt =
      static_cast<float>(std::sqrt(1.0 - std::pow(static_cast<double>(kBeta2), t)));
  k.adam(a);
  ++step_;
  last_ = m;
}

TrainingErrors TrainerImpl::Evaluate() {
  const DataSpec& s = data_.spec;
  const float* params = params_.data();
  double action_sum = 0, beacon_sum = 0, play_sum = 0;
  for (int64_t begin = 0; begin < data_.num_demo; begin += kEvalChunk) {
    const int count = static_cast<int>(std::min<int64_t>(kEvalChunk, data_.num_demo - begin));
    if (eval_.batch != count) eval_.Resize(arch_, count);
    for (int i = 0; i < count; ++i) {
      CopyRow(data_.demo_x, begin + i, s.x_dim, eval_.x.data() + i * s.x_dim);
      eval_.y[i] = data_.DemoY(begin + i);
    }
    ForwardFeatures(arch_, params, eval_);
    ForwardPolicy(arch_, params, eval_);
    action_sum +=
        SumSquaredMeanError(eval_.policy_head(), data_.demo_u.data() + begin * arch_.action_width(),
                            count, arch_.action_width());
    if (arch_.has_beacon_net()) {
      ForwardBeacon(arch_, params, eval_);
      beacon_sum += SumSquaredMeanError(eval_.beacon_head(), data_.demo_b.data() + begin * s.b_dim,
                                        count, s.b_dim);
    }
  }
  if (UsesPlay()) {
    for (int64_t begin = 0; begin < data_.num_play; begin += kEvalChunk) {
      const int count = static_cast<int>(std::min<int64_t>(kEvalChunk, data_.num_play - begin));
      if (eval_.batch != count) eval_.Resize(arch_, count);
      for (int i = 0; i < count; ++i) {
        CopyRow(data_.play_x, begin + i, s.x_dim, eval_.x.data() + i * s.x_dim);
        eval_.y[i] = data_.PlayY(begin + i);
      }
      ForwardFeatures(arch_, params, eval_);
      ForwardBeacon(arch_, params, eval_);
      play_sum += SumSquaredMeanError(eval_.beacon_head(), data_.play_b.data() + begin * s.b_dim,
                                      count, s.b_dim);
    }
  }
  TrainingErrors e;
  e.action = action_sum / static_cast<double>(data_.num_demo * arch_.action_width());
  if (arch_.has_beacon_net()) {
    e.beacon_and_play = beacon_sum / static_cast<double>(data_.num_demo * s.b_dim);
    if (UsesPlay()) e.beacon_and_play += play_sum / static_cast<double>(data_.num_play * s.b_dim);
  }
  return e;
}

bool TrainerImpl::NeedsRestart() {
  // Non-finite errors (possible only through overflow in inference) also count as failure.
  const TrainingErrors e = Evaluate();
  const bool action_bad = !(e.action <= train_.restart_action_threshold);
  const bool beacon_bad =
      arch_.has_beacon_net() && !(e.beacon_and_play <= train_.restart_beacon_threshold);
  return action_bad || beacon_bad;
}

TrainResult TrainerImpl::Train(const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  TrainResult result;
  while (!finished_) {
    while (step_ < train_.steps) {
      if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) {
        result.cancelled = true;
        break;
      }
      Step();
      if (observer_) observer_(last_);
    }
    if (result.cancelled) break;
    if (train_.restart_rule && attempt_ + 1 < train_.max_attempts && NeedsRestart()) {
      StartAttempt(attempt_ + 1);
    } else {
      finished_ = true;
    }
  }
  result.attempts = attempt_ + 1;
  result.steps_run = step_;
  result.final_metrics = last_;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

TrainerState TrainerImpl::State() const {
  TrainerState s;
  s.attempt = attempt_;
  s.step = step_;
  s.finished = finished_;
  s.adam_step = adam_step_;
  s.batch_rng = batch_rng_.GetState();
  s.noise_rng = noise_rng_.GetState();
  s.augment_rng = augment_rng_.GetState();
  s.last = last_;
  s.params.assign(params_.begin(), params_.end());
  s.exp_avg.assign(exp_avg_.begin(), exp_avg_.end());
  s.exp_avg_sq.assign(exp_avg_sq_.begin(), exp_avg_sq_.end());
  return s;
}

void TrainerImpl::SetState(const TrainerState& s) {
  const size_t n = params_.size();
  if (s.params.size() != n || s.exp_avg.size() != n || s.exp_avg_sq.size() != n) {
    throw UserError("checkpoint holds " + std::to_string(s.params.size()) +
                    " parameters but its configuration describes " + std::to_string(n) +
                    ": the architecture differs");
  }
  if (s.step < 0 || s.step > train_.steps || s.attempt < 0 || s.adam_step < 0) {
    throw UserError("checkpoint state is inconsistent (step " + std::to_string(s.step) +
                    ", attempt " + std::to_string(s.attempt) + ")");
  }
  attempt_ = s.attempt;
  step_ = s.step;
  finished_ = s.finished;
  adam_step_ = s.adam_step;
  batch_rng_.SetState(s.batch_rng);
  noise_rng_.SetState(s.noise_rng);
  augment_rng_.SetState(s.augment_rng);
  last_ = s.last;
  params_.assign(s.params.begin(), s.params.end());
  exp_avg_.assign(s.exp_avg.begin(), s.exp_avg.end());
  exp_avg_sq_.assign(s.exp_avg_sq.begin(), s.exp_avg_sq.end());
}

std::shared_ptr<PolicyImpl> TrainerImpl::MakePolicy() const {
  return std::make_shared<PolicyImpl>(arch_, std::vector<float>(params_.begin(), params_.end()),
                                      scaling_);
}

// --- Trainer ------------------------------------------------------------------------------------

Trainer::Trainer() = default;
Trainer::Trainer(const Dataset& data, const NetworkConfig& network, const TrainConfig& train)
    : impl_(std::make_unique<TrainerImpl>(data, network, train)) {}
Trainer::~Trainer() = default;

void Trainer::SetObserver(std::function<void(const StepMetrics&)> observer) {
  impl_->set_observer(std::move(observer));
}

TrainResult Trainer::Train(const std::atomic<bool>* cancel) { return impl_->Train(cancel); }
int Trainer::step() const { return impl_->step(); }
Policy Trainer::policy() const { return Policy(impl_->MakePolicy()); }
const NetworkConfig& Trainer::network_config() const { return impl_->network(); }
const TrainConfig& Trainer::train_config() const { return impl_->train(); }

}  // namespace recon::learn
