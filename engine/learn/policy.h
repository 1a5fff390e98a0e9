#pragma once

// A trained policy, as everything outside engine/learn sees it: plain types, no Torch
// (learner.h, which trains them, includes this).

#include <memory>
#include <vector>

#include "engine/core/dataset.h"

namespace recon::learn {

class PolicyImpl;

/// A trained policy: (x, y) -> action. Never needs a beacon. Cheap to copy (shares weights);
/// safe to call from one thread at a time.
class Policy {
 public:
  Policy();
  explicit Policy(std::shared_ptr<PolicyImpl> impl);
  ~Policy();
  Policy(const Policy&);
  Policy& operator=(const Policy&);

  /// A deep ensemble (Lakshminarayanan et al.): one policy whose actions (and chunks, and
  /// feature gate) are the mean of its members' mean predictions. The members are models of the
  /// same shapes and chunking trained from different seeds; averaging them takes out what one
  /// training run's seed alone decided (on 4 tabletop demonstrations a run grasps in most new
  /// scenes or in almost none, docs/results.md). Features and beacon predictions, which do not
  /// average across models, are the first member's. UserError if the list is empty or the
  /// members differ in data shapes, chunk or ensembled actions.
  static Policy Ensemble(const std::vector<Policy>& members);
  /// How many models act (1 for a trained or loaded policy).
  int ensemble_size() const;

  const DataSpec& spec() const;
  /// Mean action for one observation.
  std::vector<float> Act(const std::vector<float>& x, const std::vector<float>& y) const;
  /// Mean actions for many observations at once (rows), much faster than one at a time.
  /// `gates` (optional) receives each row's feature gate g(x) (FeatureGate; 1 without one).
  std::vector<std::vector<float>> ActBatch(const std::vector<std::vector<float>>& xs,
                                           const std::vector<std::vector<float>>& ys,
                                           std::vector<float>* gates = nullptr) const;
  /// Actions the policy predicts at once (NetworkConfig::action_chunk; 1 without chunking).
  int action_chunk() const;
  /// The actions acted on as the chunks' ensemble (NetworkConfig::ensembled_actions).
  const std::vector<int>& ensembled_actions() const;
  /// The whole predicted chunk per observation: action_chunk() actions of u_dim values, the
  /// current step's first. Act and ActBatch return only its first action; a robot that acts on
  /// chunks averages them over steps with an ActionEnsembler.
  std::vector<std::vector<float>> ActChunkBatch(const std::vector<std::vector<float>>& xs,
                                                const std::vector<std::vector<float>>& ys,
                                                std::vector<float>* gates = nullptr) const;
  /// Whether the policy has a feature gate (NetworkConfig::feature_gate_hidden).
  bool has_feature_gate() const;
  /// How open the feature gate is for this observation, g(x) in [0, 1] (it reads x alone; 1
  /// without a gate): how much of the camera's features the policy acts on here.
  float FeatureGate(const std::vector<float>& x, const std::vector<float>& y) const;
  /// The beacon net's mean prediction from the features of (x, y) (RECON only; empty for a
  /// Baseline). Lets a user see what the features learned to track.
  std::vector<float> PredictBeacon(const std::vector<float>& x, const std::vector<float>& y) const;
  /// The feature vector phi = f(x, y).
  std::vector<float> Features(const std::vector<float>& x, const std::vector<float>& y) const;
  /// Features of many observations at once (rows); an ensemble's are its first member's.
  std::vector<std::vector<float>> FeaturesBatch(const std::vector<std::vector<float>>& xs,
                                                const std::vector<std::vector<float>>& ys) const;
  /// How the action would change with each pixel value: d a_j / d y_i of Act(x, y), u_dim rows
  /// of y's size, per pixel value as recorded (0-255); an ensemble's is its members' mean. The
  /// input gradient a saliency map is made of. UserError for a policy without a camera image.
  std::vector<std::vector<float>> ActionImageJacobian(const std::vector<float>& x,
                                                      const std::vector<float>& y) const;

 private:
  std::shared_ptr<PolicyImpl> impl_;
  std::vector<std::shared_ptr<PolicyImpl>> others_;  ///< Ensemble's members after the first
};

}  // namespace recon::learn
