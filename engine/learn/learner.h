#pragma once

// The RECON learner, behind a header that does not include Torch: everything outside
// engine/learn sees only these plain types, so it compiles in a second and never links Torch
// unless it trains.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/learn/policy.h"

namespace recon::learn {

/// Which objective is trained.
enum class Method {
  kRecon,     ///< action + beacon (+ play) terms
  kBaseline,  ///< the same feature and policy networks, action term only
};

/// How a Gaussian head is scored against its target.
enum class LossKind {
  kNll,        ///< the paper: Gaussian negative log-likelihood with a learned log-variance
  kMseSample,  ///< the authors' code: MSE of a reparameterised sample (mean + std * noise)
};

/// What computes each training step's gradient. Both train the same model from the same state
/// (weights, Adam moments, generators), so checkpoints and results are interchangeable; they
/// differ only in rounding.
enum class Backend {
  kFused,  ///< our own kernels (kernels.h): the default and the fastest
  /// LibTorch operators and autograd, for users who want to train with Torch and compare; about
  /// 3x slower per step. Deterministic per seed on one thread (SetThreads(1), the default).
  kTorch,
};

/// What the feature gate (NetworkConfig::feature_gate_hidden) learns to predict per sample, i.e.
/// where the camera is worth reading (TrainConfig::gate_margin sets the threshold).
enum class GateTarget {
  /// Where the seeing branch's action loss is lower than the blind branch's by more than the
  /// margin (nats per action). On a few demonstrations it marks nearly every sample: seeing helps
  /// memorise them.
  kLoss,
  /// Where the teacher did something else in another demonstration at the nearest state: the
  /// largest, over the other demonstrations, of the squared difference per action between this
  /// sample's chunk and the best-matching chunk within 5 steps of the other demonstration's
  /// nearest robot state, in units of the actions' total variance, exceeds the margin for at
  /// least two chunks' rows in a row (gate_targets.h: shorter is timing). Fixed before training,
  /// from the data alone (no beacons: the Baseline gets the same targets). Where every
  /// demonstration agrees, the state alone says what to do, so the image cannot be needed there.
  /// Each sample then trains only the branch its target picks (seeing where 1, blind where 0),
  /// as if the features were masked where the gate shuts: a seeing branch trained on every
  /// sample learns to read the features where they only help it memorise.
  kDisagreement,
};

/// How the learning rate moves over a training run.
enum class LrSchedule {
  kConstant,  ///< TrainConfig::learning_rate throughout (the authors')
  /// Cosine decay from TrainConfig::learning_rate at the first step to 0 after the last
  /// (Loshchilov and Hutter, SGDR; LeRobot's default): the weights settle at the end of the run
  /// instead of being a snapshot of Adam's noise at a large rate, which made the tabletop's
  /// outcome depend on the training seed (docs/results.md).
  kCosine,
};

Method ParseMethod(const std::string& name);          ///< "recon" | "baseline"; UserError otherwise
LossKind ParseLossKind(const std::string& name);      ///< "nll" | "mse-sample"; UserError otherwise
Backend ParseBackend(const std::string& name);        ///< "fused" | "torch"; UserError otherwise
GateTarget ParseGateTarget(const std::string& name);  ///< "loss" | "disagreement"; UserError
LrSchedule ParseLrSchedule(const std::string& name);  ///< "constant" | "cosine"; UserError
std::string ToString(Method method);
std::string ToString(LossKind loss);
std::string ToString(Backend backend);
std::string ToString(GateTarget target);
std::string ToString(LrSchedule schedule);
/// The learning rate of 0-based step `step` of a `steps`-step run.
double ScheduledLearningRate(double learning_rate, LrSchedule schedule, int step, int steps);

/// Architecture. The defaults are the authors' networks for 3x32x32 images (REFERENCE.md 2).
struct NetworkConfig {
  int feature_dim = 6;  ///< k; must exceed the beacon dimension d for RECON

  // Image feature network (y is {C, H, W}): per entry of conv_channels a conv(kernel) + ReLU +
  // maxpool(2) block, then fully connected layers with ReLU, then a linear layer to k.
  std::vector<int> conv_channels = {6, 16};
  int conv_kernel = 5;
  std::vector<int> cnn_hidden = {120, 60};
  /// y is multiplied by this before the CNN. The authors feed raw 0-255 values (scale 1).
  float image_scale = 1.0f;
  /// Replace the flattened C x H x W output of the last convolution block by 2 C keypoints: per
  /// channel, the expected image coordinates (x, y in [-1, 1]) under a softmax over the plane
  /// with a learned temperature (Levine, Finn et al., deep spatial autoencoders; robomimic's
  /// VisualCore). Off by default, the authors' networks; configs written before it read as off.
  bool spatial_softmax = false;

  // Vector feature network (y is {m}): an MLP on [x, y] with ReLU hidden layers.
  std::vector<int> feature_mlp_hidden = {64, 64};

  /// Policy on [x, phi]: first hidden layer tanh, later ones ReLU (authors), Gaussian head.
  std::vector<int> policy_hidden = {32, 32};
  /// Beacon net on phi: tanh hidden layers, Gaussian head.
  std::vector<int> beacon_hidden = {16, 16};

  /// Action chunking (Zhao et al., ACT 2023): the policy predicts the next action_chunk actions
  /// at once (trained on u_t .. u_{t+k-1}, the episode's last action repeated past its end), and
  /// an acting robot averages the overlapping predictions for the current step
  /// (ActionEnsembler). 1 (the default) = one action per step.
  int action_chunk = 1;
  /// Which actions (indices into u) the acting robot averages over the overlapping chunks; the
  /// others are taken from the newest chunk alone. Empty (the default) = every action, ACT's
  /// ensemble. A discrete command such as a gripper's close needs the average to cross its
  /// threshold at all (docs/results.md); a joint velocity taken from the newest chunk follows
  /// the state now, where an average also carries plans made up to a chunk ago (e.g. the lift
  /// after a close that came late).
  std::vector<int> ensembled_actions;
  /// A feature gate: a small network on the robot state x alone (these tanh hidden layers, then
  /// one sigmoid unit) gives g(x) in [0, 1], how much the policy looks at the features. The
  /// policy network runs twice, seeing [x, phi] and blind [x, 0], both trained on every sample,
  /// and the robot acts on g seeing + (1 - g) blind. The gate is trained as a classifier of
  /// where seeing pays: the target of a sample is 1 when the blind branch's action loss exceeds
  /// the seeing branch's by more than TrainConfig::gate_margin (per action), else 0. For the
  /// tabletop it can learn to shut the camera out of the approach to the toast (the same in
  /// every scene), so what the features pick up there (the bowl) cannot move the arm. Empty
  /// (the default) = no gate, as in the paper.
  std::vector<int> feature_gate_hidden;

  bool has_feature_gate() const { return !feature_gate_hidden.empty(); }
  bool operator==(const NetworkConfig& other) const = default;
};

/// The largest square TrainConfig::random_erase_px accepts (in pixels).
constexpr int kMaxRandomErasePx = 64;
/// The largest TrainConfig::feature_noise accepted (in standard deviations of each feature).
constexpr double kMaxFeatureNoise = 10.0;
/// The largest TrainConfig::beacon_filter_samples accepted: longer than any episode.
constexpr int kMaxBeaconFilterSamples = 100000;
/// The largest TrainConfig::play_consistency accepted.
constexpr double kMaxPlayConsistency = 100.0;
/// The largest TrainConfig::nll_min_std accepted (in the targets' units).
constexpr double kMaxNllMinStd = 10.0;
/// The largest TrainConfig::gate_margin accepted (nats per action).
constexpr double kMaxGateMargin = 100.0;
/// The largest TrainConfig::weight_decay accepted (per unit of learning rate; with the tabletop's
/// rate of 1e-3 it takes 1 % off every weight per step).
constexpr double kMaxWeightDecay = 10.0;
/// The smallest TrainConfig::learning_rate accepted. The kernels step in float: far below it a
/// step changes no weight (1e-300 is 0 in float) and the moments go subnormal, which only slows
/// the run; a typo of the exponent is refused instead of trained for hours to no effect.
constexpr double kMinLearningRate = 1e-9;

/// The training recipe. Defaults are the authors' (REFERENCE.md 2) except the loss and its
/// weights, which are the paper's: an unweighted sum of negative log-likelihoods (eq. 6).
/// AuthorsRecipe() gives the authors' code exactly (MSE of a sample, weights 1.0 / 1.2 / 1.2).
struct TrainConfig {
  Method method = Method::kRecon;
  LossKind loss = LossKind::kNll;
  double learning_rate = 4e-4;  ///< Adam
  /// Checkpoints written before the choice existed read as kConstant.
  LrSchedule lr_schedule = LrSchedule::kConstant;
  int batch_size = 20;  ///< drawn with replacement each step, from demos and from play
  int steps = 6001;
  double action_weight = 1.0;
  double beacon_weight = 1.0;
  double play_weight = 1.0;
  /// The authors' rule: retrain from scratch (new seed stream) if, at the end, the action error
  /// exceeds restart_action_threshold or the beacon + play error exceeds
  /// restart_beacon_threshold. Judged on the mean squared error of the heads' mean predictions
  /// over the whole training set, so the rule means the same under either loss kind.
  /// Train on standardised targets (u and b shifted and scaled to zero mean and unit spread per
  /// dimension, fitted on the training data and stored with the model; outputs are mapped back).
  /// Keeps the NLL from stalling on large targets (target_scaling.h). Losses and the restart
  /// rule's errors are then in standardised units. The authors' recipe trains on raw targets.
  bool standardize_targets = true;
  /// Also standardise the inputs: the robot state x (and a vector y) per dimension, from the
  /// training data, stored with the model and applied when acting (robomimic and LeRobot do).
  /// Off by default, so models and results without it are unchanged.
  bool standardize_inputs = false;
  bool restart_rule = false;
  int max_attempts = 5;
  double restart_action_threshold = 0.1;
  double restart_beacon_threshold = 1.0;
  uint64_t seed = 0;
  /// Only the gradient's computation differs (see Backend); a checkpoint written before this
  /// setting existed reads as kFused.
  Backend backend = Backend::kFused;
  /// Random-shift augmentation of camera images (DrQ): each image of a batch is shifted by up to
  /// this many pixels per axis, border replicated, drawn from its own seeded stream. 0 = off (and
  /// no random numbers drawn, so results without it are unchanged); at most kMaxRandomShiftPx.
  int random_shift_px = 0;
  /// Random erasing of camera images (cutout, augmentation.h): after the shift, a square of this
  /// side (pixels) at a uniformly drawn place of each training image (demonstration and play) is
  /// painted with the image's mean colour, drawn from the augmentation stream. It shows the
  /// networks that a local change of the scene (a bowl elsewhere) need not change the action.
  /// 0 = off (nothing drawn, results unchanged); at most kMaxRandomErasePx.
  int random_erase_px = 0;
  /// Feature noise: before the policy reads the features of a demonstration batch, each one is
  /// perturbed by feature_noise times its standard deviation over the batch (Gaussian, from the
  /// augmentation stream; the spread is held constant in the gradient). The beacon net reads them
  /// clean. It keeps the policy flat in directions the demonstrations never varied (a bowl where
  /// no demonstration had it), which otherwise move the arm off the toast. Relative to the
  /// spread, so the feature net cannot outgrow it by scaling up. 0 = off (nothing drawn, results
  /// unchanged); at most kMaxFeatureNoise.
  double feature_noise = 0.0;
  /// Beacon readings smoothed before they are trained on (beacon_filter.h): each reading of a
  /// demonstration, or of a play chunk (Dataset::play_chunks), becomes the mean of the readings
  /// up to this many samples before and after it in the same episode or chunk. A UWB beacon's
  /// noise (about 7 cm per axis on a DWM1001) is independent from sample to sample, and a feature
  /// net trained on raw readings learns each frame's noise by heart. 0 = raw readings (results
  /// without it are unchanged); at most kMaxBeaconFilterSamples. Checkpoints from before read 0.
  int beacon_filter_samples = 0;
  /// Weight of RECON's play-consistency term (play_consistency.h): the features of two play
  /// samples of the same chunk (one beacon placement, the marked object still, the others moved)
  /// are asked to agree, relative to their spread over the play batch. Play pairs are then drawn
  /// from one chunk each. The Baseline and runs without play data ignore it. 0 = off (results
  /// unchanged); at most kMaxPlayConsistency. Checkpoints from before read 0.
  double play_consistency = 0.0;
  /// A floor under the standard deviation of every Gaussian head's NLL (LossKind::kNll), in the
  /// targets' units (standardised ones by default): below it the log-variance is held at the
  /// floor and gets no gradient. The NLL of a target that repeats exactly (a gripper command
  /// of 0 or 1) falls without bound as its variance shrinks, so an unfloored head keeps
  /// sharpening with training and weighs each sample by 1/variance; with 30,000 steps on 20
  /// tabletop demonstrations the Baseline's loss reached -15 nats and its arm stopped closing
  /// the gripper (docs/results.md). 0 = no floor (results unchanged); at most kMaxNllMinStd.
  /// Checkpoints from before read 0.
  double nll_min_std = 0.0;
  /// A floor like nll_min_std under the policy head's standard deviation of single actions
  /// (indices into u, every action of a chunk): empty (the default) = none, else one value per
  /// action, 0 = none for that action. The tabletop's gripper command (0 or 1, repeated exactly
  /// within each phase) is where the spread collapses; its joint velocities are continuous, and
  /// a floor on every dimension blurs them too (docs/results.md). Where both are set the higher
  /// floor holds. Each at most kMaxNllMinStd. Checkpoints from before read empty.
  std::vector<double> action_min_std;
  /// Decoupled weight decay (AdamW, Loshchilov & Hutter): before each Adam step every weight of
  /// every layer (linear weights and convolution kernels; biases and the spatial softmax's
  /// temperature excluded) is multiplied by 1 - lr_t * weight_decay, lr_t the step's scheduled
  /// rate. A weight that no demonstration's gradient holds up (the response to a feature
  /// direction the demonstrations never varied, a bowl where none had it) decays towards 0
  /// instead of keeping its random initial value. Applies to every method alike. 0 = off
  /// (results unchanged); at most kMaxWeightDecay. Checkpoints from before read 0.
  double weight_decay = 0.0;
  /// The floor nll_min_std as a log-variance (-infinity without one).
  float NllMinLogVar() const;
  /// Per dimension of the policy head's mean (chunk x u_dim, as the training targets): the
  /// log-variance floor from nll_min_std and action_min_std.
  std::vector<float> PolicyMinLogVar(int u_dim, int chunk) const;
  /// With a feature gate (NetworkConfig::feature_gate_hidden): how much the features must lower
  /// a sample's action loss (per action; nats under the NLL) for the gate to learn to open
  /// there (GateTarget::kLoss), or how much the demonstrations must disagree
  /// (GateTarget::kDisagreement, in units of the actions' total variance). The loss gains the blind
  /// branch's action term and the gate's binary cross-entropy against these targets (held constant
  /// in the gradient: the gate does not push either branch). A first version trained g L(seeing) +
  /// (1 - g) L(blind) + margin g instead: its gate saturated shut everywhere within the first
  /// steps, before the seeing branch had learnt where it pays, and a saturated sigmoid has no
  /// gradient to reopen.
  double gate_margin = 0.0;
  /// What the gate's targets mark (GateTarget); gate_margin is in its units.
  GateTarget gate_target = GateTarget::kLoss;

  bool operator==(const TrainConfig& other) const = default;
};

/// The authors' code: MSE of a reparameterised sample, weights 1.0 / 1.2 / 1.2, restart rule on.
TrainConfig AuthorsRecipe();

/// Losses of one training step (per-sample means). Terms that are off are 0.
struct StepMetrics {
  int attempt = 0;  ///< 0 for the first try, 1.. after restarts
  int step = 0;     ///< 0-based step within the attempt
  float action_loss = 0;
  float beacon_loss = 0;
  float play_loss = 0;
  float consistency_loss = 0;  ///< TrainConfig::play_consistency's term (unweighted)
  float total_loss = 0;
  float gate_mean = 1;   ///< the feature gate's mean over the batch (1: no gate, always open)
  float blind_loss = 0;  ///< the gate's blind branch: its action term (as action_loss)
  float gate_loss = 0;   ///< the gate's cross-entropy against where seeing pays
};

struct TrainResult {
  int attempts = 1;   ///< tries used (restart rule)
  int steps_run = 0;  ///< steps of the final attempt
  StepMetrics final_metrics;
  double seconds = 0;
  bool cancelled = false;
};

/// Sets Torch's intra-op thread count for this process (the `--threads` setting). Training
/// itself runs on the calling thread (one core per Trainer, no allocation per step): to use
/// more cores, train several models at once, as experiment sweeps do.
void SetThreads(int threads);

class TrainerImpl;

/// Trains the feature, beacon and policy networks on a Dataset.
///
/// Construction validates the data (ValidateDataset) and the configuration (k > d for RECON,
/// positive steps and batch) and throws UserError with a clear message otherwise. Training is
/// deterministic for a given seed on one thread. A step whose loss is NaN or infinite stops
/// training with DivergenceError before the weights are touched.
///
/// Determinism holds per machine: the same seed gives bitwise the same model however many
/// trainers run at once, but CPUs with different vector units (AVX-512, AVX2, none) round
/// differently. A Trainer is used from one thread at a time; separate Trainers are independent.
class Trainer {
 public:
  Trainer(const Dataset& data, const NetworkConfig& network, const TrainConfig& train);
  ~Trainer();
  Trainer(const Trainer&) = delete;
  Trainer& operator=(const Trainer&) = delete;

  /// Called after every step (from the training thread).
  void SetObserver(std::function<void(const StepMetrics&)> observer);

  /// Runs the remaining steps (all of them for a fresh trainer, the rest after Resume), applying
  /// the restart rule if configured. Returns early, with cancelled = true, when *cancel becomes
  /// true; the trainer can then be checkpointed and resumed.
  TrainResult Train(const std::atomic<bool>* cancel = nullptr);

  int step() const;  ///< steps done in the current attempt
  /// The current model as an inference-only policy (a copy of the weights).
  Policy policy() const;

  /// Writes model, optimizer state, both configs, step, RNG state and the dataset fingerprint
  /// to one file, atomically (temporary file + rename).
  void SaveCheckpoint(const std::string& path) const;
  /// Reopens a checkpoint to continue training on `data`. UserError if the file is missing or
  /// corrupt, or the data's fingerprint or shapes differ from those it was trained on.
  /// `backend`, if given, replaces the stored one: either backend continues any checkpoint.
  static std::unique_ptr<Trainer> Resume(const std::string& path, const Dataset& data,
                                         std::optional<Backend> backend = std::nullopt);

  const NetworkConfig& network_config() const;
  const TrainConfig& train_config() const;

 private:
  Trainer();
  std::unique_ptr<TrainerImpl> impl_;
};

/// Loads the policy stored in a checkpoint. UserError if missing, corrupt, or not a checkpoint.
Policy LoadPolicy(const std::string& checkpoint_path);

/// The name of the fused kernel table training runs on ("generic", "avx2" or "avx512"; the
/// best this CPU has unless RECON_KERNELS chose one). Training is chaotic under rounding, so two
/// kernel tables (or two CPUs) give different models from the same seeds: experiments record it.
std::string KernelsInUse();

}  // namespace recon::learn
