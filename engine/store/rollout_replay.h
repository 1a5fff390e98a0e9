#pragma once

// The rollouts of one method on a session's test scenes, kept so that they can be played back
// frame by frame later (the studio shows the Baseline and RECON side by side on the same scene).
// One HDF5 file per method, rollouts/<method>.replay.h5 next to rollouts/<method>.json:
//
//   /                  attrs recon_kind = "rollout_replay", recon_format (1), world, method,
//                            state_size, num_scenarios
//   /scenario_<i>      attrs seed, metric, succeeded            (i = 0 .. num_scenarios - 1)
//   /scenario_<i>/states   float64 (T, state_size)   World::ReplayState() after the reset and
//                                                    after each step (T = EpisodeLength() + 1)
//
// Each scenario is its own dataset (one chunk, gzipped and checksummed with Fletcher-32), so a
// viewer reads only the scene it shows and a damaged chunk is an error rather than a wrong
// picture. Seeds are stored as int64 with the uint64's bits, as episode files do.

#include <cstdint>
#include <string>
#include <vector>

#include "engine/store/h5.h"

namespace recon::store {

/// One test scenario's rollout: how it ended and the states to draw each step again.
struct ScenarioReplay {
  uint64_t seed = 0;  ///< the scenario seed (World::Reset)
  double metric = 0;  ///< World::EpisodeMetric() at the end
  bool succeeded = false;
  std::vector<std::vector<double>> states;  ///< T states of state_size values each, T >= 1
};

/// All test scenarios of one method.
struct RolloutReplay {
  std::string world;   ///< World::Name(), which World::ShowReplayState() takes the states
  std::string method;  ///< "baseline" or "recon"
  int state_size = 0;  ///< size of every state (World::ReplayState().size())
  std::vector<ScenarioReplay> scenarios;
};

/// Writes `replay` to `path` atomically (a temporary file, flushed to disk, renamed over `path`):
/// readers see the old file or the new one. UserError naming the scenario and state whose size
/// is not state_size, or a scenario without states, before anything is written.
void WriteRolloutReplay(const std::string& path, const RolloutReplay& replay);

/// Reads a whole replay file. UserError naming the file and the dataset or attribute that is
/// missing or wrong (and for a missing, truncated or non-HDF5 file).
RolloutReplay ReadRolloutReplay(const std::string& path);

/// A replay file kept open to read one scenario at a time: opening reads only the root's
/// attributes (and checks every scenario group is there); ReadScenario reads one dataset. Use
/// from one thread at a time.
class RolloutReplayFile {
 public:
  /// UserError naming the file and the attribute or group that is missing or wrong.
  static RolloutReplayFile Open(const std::string& path);

  const std::string& path() const { return file_.path(); }
  const std::string& world() const { return world_; }
  const std::string& method() const { return method_; }
  int state_size() const { return state_size_; }
  int NumScenarios() const { return num_scenarios_; }
  /// Scenario `index` (0 .. NumScenarios() - 1; std::out_of_range otherwise). UserError naming
  /// the file and the dataset or attribute when it is damaged or of the wrong shape.
  ScenarioReplay ReadScenario(int index) const;

 private:
  explicit RolloutReplayFile(h5::File file) : file_(std::move(file)) {}

  h5::File file_;
  std::string world_, method_;
  int state_size_ = 0;
  int num_scenarios_ = 0;
};

/// The group name of scenario `index`: "scenario_<index>".
std::string ScenarioGroupName(int index);

}  // namespace recon::store
