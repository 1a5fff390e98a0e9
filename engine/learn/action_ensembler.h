#pragma once

// Temporal ensembling of action chunks (Zhao et al., ACT 2023). A policy that predicts the next k
// actions at every step has, for the current step, up to k predictions made at the last k steps.
// Acting on their weighted mean, w_i = exp(-m i) with i = 0 the oldest prediction, smooths the
// motion and lets an early, committed plan outvote a single step's jitter. Actions left out of
// the ensemble come from the newest prediction alone (NetworkConfig::ensembled_actions).

#include <deque>
#include <vector>

namespace recon::learn {

class ActionEnsembler {
 public:
  /// `chunk` actions of `action_dim` values per prediction; `m` >= 0 (ACT's 0.01). `ensembled`
  /// lists the actions averaged over the predictions; empty = all of them.
  ActionEnsembler(int chunk, int action_dim, double m = 0.01,
                  const std::vector<int>& ensembled = {});

  /// Adds this step's prediction (chunk * action_dim values, the current step's action first)
  /// and returns the action to execute now. Call once per step, in order.
  std::vector<float> Step(const std::vector<float>& chunk_prediction);
  /// Forgets every prediction (a new episode).
  void Reset() { predictions_.clear(); }

  /// The weights Step applies to the predictions it holds for the current step, oldest first
  /// (normalised to sum 1), when `count` predictions overlap it.
  std::vector<double> Weights(int count) const;

 private:
  int chunk_, action_dim_;
  double m_;
  std::vector<bool> ensembled_;  ///< per action: averaged (true) or the newest prediction's
  /// The predictions still covering the current step, oldest first; each is trimmed at the
  /// front as steps pass, so its first action is always the current step's.
  std::deque<std::vector<float>> predictions_;
};

}  // namespace recon::learn
