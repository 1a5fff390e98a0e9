#pragma once

#include <string>
#include <vector>

#include "engine/learn/learner.h"

namespace recon::experiments {

/// One bar of a result figure: how the beacons are placed and how the learner is trained.
struct Condition {
  std::string name;       ///< as typed on the command line, e.g. "exact", "exact-sigma2.5"
  std::string label;      ///< as drawn in figures, e.g. "Exact", "Exact σ=2.5"
  std::string placement;  ///< the world's beacon placement ("none" for the Baseline)
  double noise_sigma = 0.0;
  learn::Method method = learn::Method::kRecon;
  bool use_play = false;  ///< train the beacon term on play data too
};

/// Parses the condition names of an experiment on `world` ("dynamic2d" or "static2d") and adds
/// one Exact condition per noise level. Throws UserError naming the unknown condition and listing
/// the valid ones; duplicates are rejected too.
std::vector<Condition> ParseConditions(const std::string& world,
                                       const std::vector<std::string>& names,
                                       const std::vector<double>& exact_noise_levels);

/// The conditions an experiment runs when none are given (the paper's figure).
std::vector<std::string> DefaultConditionNames(const std::string& world);
/// Every condition name the world accepts (for help texts and error messages).
std::vector<std::string> KnownConditionNames(const std::string& world);

}  // namespace recon::experiments
