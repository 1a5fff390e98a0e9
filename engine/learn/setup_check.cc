#include "engine/learn/setup_check.h"

#include "engine/learn/augmentation.h"

#include <cmath>
#include <sstream>
#include <string>

#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace recon::learn {

namespace {

void CheckWeight(double weight, const char* name) {
  if (!std::isfinite(weight) || weight < 0) {
    std::ostringstream msg;
    msg << "train config: " << name << " must be finite and >= 0 (got " << weight << ")";
    throw UserError(msg.str());
  }
}

// A setting that must be a finite number in [0, max]; `unit` follows max in the message.
void CheckBetweenZeroAnd(double value, double max, const std::string& name, const char* unit = "") {
  if (!std::isfinite(value) || value < 0 || value > max) {
    throw UserError("train config: " + name + " must be between 0 and " + FormatNumber(max) + unit +
                    " (got " + FormatNumber(value) + ")");
  }
}

}  // namespace

void CheckTrainingSetup(const Dataset& data, const NetworkConfig& network,
                        const TrainConfig& train) {
  if (train.steps <= 0) {
    throw UserError("train config: steps must be positive (got " + std::to_string(train.steps) +
                    ")");
  }
  if (train.batch_size <= 0) {
    throw UserError("train config: batch_size must be positive (got " +
                    std::to_string(train.batch_size) + ")");
  }
  if (!std::isfinite(train.learning_rate) || train.learning_rate < kMinLearningRate) {
    std::ostringstream msg;
    msg << "train config: learning_rate must be at least " << kMinLearningRate << " (got "
        << train.learning_rate << ")";
    throw UserError(msg.str());
  }
  CheckWeight(train.action_weight, "action_weight");
  CheckWeight(train.beacon_weight, "beacon_weight");
  CheckWeight(train.play_weight, "play_weight");
  if (train.restart_rule && train.max_attempts < 1) {
    throw UserError("train config: max_attempts must be at least 1 (got " +
                    std::to_string(train.max_attempts) + ")");
  }
  if (train.random_shift_px < 0 || train.random_shift_px > kMaxRandomShiftPx) {
    throw UserError("train config: random_shift_px must be between 0 and " +
                    std::to_string(kMaxRandomShiftPx) + " pixels (got " +
                    std::to_string(train.random_shift_px) + ")");
  }
  if (train.random_erase_px < 0 || train.random_erase_px > kMaxRandomErasePx) {
    throw UserError("train config: random_erase_px must be between 0 and " +
                    std::to_string(kMaxRandomErasePx) + " pixels (got " +
                    std::to_string(train.random_erase_px) + ")");
  }
  CheckBetweenZeroAnd(train.gate_margin, kMaxGateMargin, "gate_margin");
  CheckBetweenZeroAnd(train.weight_decay, kMaxWeightDecay, "weight_decay");
  CheckBetweenZeroAnd(train.feature_noise, kMaxFeatureNoise, "feature_noise",
                      " standard deviations");
  if (train.beacon_filter_samples < 0 || train.beacon_filter_samples > kMaxBeaconFilterSamples) {
    throw UserError("train config: beacon_filter_samples must be between 0 and " +
                    std::to_string(kMaxBeaconFilterSamples) + " (got " +
                    std::to_string(train.beacon_filter_samples) + ")");
  }
  CheckBetweenZeroAnd(train.play_consistency, kMaxPlayConsistency, "play_consistency");
  CheckBetweenZeroAnd(train.nll_min_std, kMaxNllMinStd, "nll_min_std");
  if (!train.action_min_std.empty()) {
    if (static_cast<int>(train.action_min_std.size()) != data.spec.u_dim) {
      throw UserError("train config: action_min_std has " +
                      std::to_string(train.action_min_std.size()) +
                      " values, but the actions have " + std::to_string(data.spec.u_dim) +
                      " (one per action, or none)");
    }
    for (size_t a = 0; a < train.action_min_std.size(); ++a) {
      CheckBetweenZeroAnd(train.action_min_std[a], kMaxNllMinStd,
                          "action_min_std[" + std::to_string(a) + "]");
    }
  }
  ValidateDataset(data, "training data");
  if (train.random_shift_px > 0 && !data.spec.YIsImage()) {
    throw UserError(
        "train config: random_shift_px (--random-shift) shifts camera images, but y is a "
        "vector (" +
        data.spec.ToString() + "); set it to 0");
  }
  if (train.random_erase_px > 0 && !data.spec.YIsImage()) {
    throw UserError(
        "train config: random_erase_px erases squares of camera images (--random-erase), "
        "but y is a vector (" +
        data.spec.ToString() + "); set it to 0");
  }
  if (train.method == Method::kRecon) {
    const int d = data.spec.b_dim, k = network.feature_dim;
    if (d == 0) {
      throw UserError(
          "RECON needs beacon readings, but the data has none (beacon dimension d=0): place a "
          "beacon before recording, or train the Baseline");
    }
    if (k <= d) {
      throw UserError("feature size k=" + std::to_string(k) +
                      " must exceed beacon dimension d=" + std::to_string(d) +
                      " for RECON (the features must be able to hold more than the beacons): "
                      "raise feature_dim to at least " +
                      std::to_string(d + 1));
    }
  }
}

}  // namespace recon::learn
