#pragma once

#include <array>
#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "engine/learn/action_ensembler.h"
#include "engine/learn/policy.h"
#include "engine/store/real_trials.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The trials under way: the policy, the trial's layout and what it has done so far.
struct TrialRun {
  std::string method, label;
  std::optional<std::string> model_id;
  learn::Policy policy;
  std::optional<learn::ActionEnsembler> ensembler;
  uint64_t test_seed = 0;
  int first = 0, last = 0, number = 0;
  ui::TrialPhase phase = ui::TrialPhase::kSetUp;
  uint64_t scene_seed = 0;
  std::map<std::string, std::array<double, 2>> layout;
  std::chrono::steady_clock::time_point starts;  ///< the countdown's end; then homing's start
  double homing_from_rad = 0;  ///< the largest joint distance from home when homing began
  float homing_progress = 0;
  int step = 0;
  bool stopped = false;
  store::TrialFrames frames;
  std::string message;
};

}  // namespace recon::studio
