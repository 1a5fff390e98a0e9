#include "engine/learn/action_ensembler.h"

#include <cmath>

#include "engine/core/error.h"

namespace recon::learn {

ActionEnsembler::ActionEnsembler(int chunk, int action_dim, double m,
                                 const std::vector<int>& ensembled)
    : chunk_(chunk), action_dim_(action_dim), m_(m) {
  if (chunk < 1 || action_dim < 1) {
    throw UserError("an action ensembler needs a chunk and an action size of at least 1");
  }
  if (!std::isfinite(m) || m < 0) {
    throw UserError("the ensembling weight m must be a non-negative number");
  }
  ensembled_.assign(static_cast<size_t>(action_dim), ensembled.empty());
  for (int a : ensembled) {
    if (a < 0 || a >= action_dim) {
      throw UserError("an ensembled action must be one of 0-" + std::to_string(action_dim - 1) +
                      ", not " + std::to_string(a));
    }
    ensembled_[static_cast<size_t>(a)] = true;
  }
}

std::vector<double> ActionEnsembler::Weights(int count) const {
  std::vector<double> w(static_cast<size_t>(count));
  double sum = 0;
  for (int i = 0; i < count; ++i) sum += w[i] = std::exp(-m_ * i);
  for (double& v : w) v /= sum;
  return w;
}

std::vector<float> ActionEnsembler::Step(const std::vector<float>& chunk_prediction) {
  if (static_cast<int>(chunk_prediction.size()) != chunk_ * action_dim_) {
    throw UserError("an action chunk has " + std::to_string(chunk_ * action_dim_) +
                    " values, got " + std::to_string(chunk_prediction.size()));
  }
  predictions_.push_back(chunk_prediction);
  const std::vector<double> w = Weights(static_cast<int>(predictions_.size()));
  std::vector<double> sum(static_cast<size_t>(action_dim_), 0.0);
  for (size_t p = 0; p < predictions_.size(); ++p) {
    for (int k = 0; k < action_dim_; ++k) sum[k] += w[p] * predictions_[p][k];
  }
  for (int k = 0; k < action_dim_; ++k) {
    if (!ensembled_[static_cast<size_t>(k)]) sum[k] = predictions_.back()[k];
  }
  // Move every prediction on by one step; the oldest runs out when its chunk is used up.
  for (std::vector<float>& p : predictions_) p.erase(p.begin(), p.begin() + action_dim_);
  while (!predictions_.empty() && predictions_.front().empty()) predictions_.pop_front();
  return std::vector<float>(sum.begin(), sum.end());
}

}  // namespace recon::learn
