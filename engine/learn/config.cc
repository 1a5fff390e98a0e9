// Names and presets of the learner's settings (learner.h).

#include "engine/core/error.h"
#include "engine/learn/learner.h"

namespace recon::learn {

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

std::string ToString(Method method) { return method == Method::kRecon ? "recon" : "baseline"; }

std::string ToString(LossKind loss) { return loss == LossKind::kNll ? "nll" : "mse-sample"; }

std::string ToString(Backend backend) { return backend == Backend::kFused ? "fused" : "torch"; }

std::string ToString(GateTarget target) {
  return target == GateTarget::kLoss ? "loss" : "disagreement";
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
