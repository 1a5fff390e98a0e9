// Names and presets of the learner's settings (learner.h).

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "engine/learn/learner.h"

namespace recon::learn {

float TrainConfig::NllMinLogVar() const {
  if (nll_min_std <= 0) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(2.0 * std::log(nll_min_std));
}

std::vector<float> TrainConfig::PolicyMinLogVar(int u_dim, int chunk) const {
  std::vector<float> floors(static_cast<size_t>(u_dim) * chunk, NllMinLogVar());
  if (action_min_std.empty()) return floors;
  for (size_t j = 0; j < floors.size(); ++j) {
    const double s = action_min_std[j % u_dim];
    if (s > 0) floors[j] = std::max(floors[j], static_cast<float>(2.0 * std::log(s)));
  }
  return floors;
}

Method ParseMethod(const std::string& name) {
  if (name == "recon") return Method::kRecon;
  if (name == "baseline") return Method::kBaseline;
  throw UserError("unknown method '" + name + "' (expected recon or baseline)");
}

LossKind ParseLossKind(const std::string& name) {
  if (name == "nll") return LossKind::kNll;
  if (name == "mse-sample") return LossKind::kMseSample;
  throw UserError("unknown loss '" + name + "' (expected nll or mse-sample)");
}

Backend ParseBackend(const std::string& name) {
  if (name == "fused") return Backend::kFused;
  if (name == "torch") return Backend::kTorch;
  throw UserError("unknown backend '" + name + "' (expected fused or torch)");
}

GateTarget ParseGateTarget(const std::string& name) {
  if (name == "loss") return GateTarget::kLoss;
  if (name == "disagreement") return GateTarget::kDisagreement;
  throw UserError("unknown gate target '" + name + "' (expected loss or disagreement)");
}

LrSchedule ParseLrSchedule(const std::string& name) {
  if (name == "constant") return LrSchedule::kConstant;
  if (name == "cosine") return LrSchedule::kCosine;
  throw UserError("unknown learning-rate schedule '" + name + "' (expected constant or cosine)");
}

std::string ToString(Method method) { return method == Method::kRecon ? "recon" : "baseline"; }

std::string ToString(LossKind loss) { return loss == LossKind::kNll ? "nll" : "mse-sample"; }

std::string ToString(Backend backend) { return backend == Backend::kFused ? "fused" : "torch"; }

std::string ToString(GateTarget target) {
  return target == GateTarget::kLoss ? "loss" : "disagreement";
}

std::string ToString(LrSchedule schedule) {
  return schedule == LrSchedule::kConstant ? "constant" : "cosine";
}

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double ScheduledLearningRate(double learning_rate, LrSchedule schedule, int step, int steps) {
  if (schedule == LrSchedule::kConstant || steps <= 0) return learning_rate;
  // Step 0 trains at the full rate and the last at a small positive one: (step + 1) / steps
  // would end at exactly 0, a step that changes nothing.
  const double progress = std::clamp(static_cast<double>(step) / steps, 0.0, 1.0);
  return learning_rate * 0.5 * (1.0 + std::cos(kPi * progress));
}

TrainConfig AuthorsRecipe() {
  TrainConfig config;
  config.loss = LossKind::kMseSample;
  config.learning_rate = 4e-4;
  config.batch_size = 20;
  config.steps = 6001;
  config.action_weight = 1.0;
  config.beacon_weight = 1.2;
  config.play_weight = 1.2;
  config.restart_rule = true;
  config.standardize_targets = false;
  return config;
}

}  // namespace recon::learn
