#include "engine/store/rollout_replay.h"

#include <stdexcept>
#include <utility>

#include "engine/core/error.h"
#include "engine/store/atomic_file.h"

namespace recon::store {

namespace {

constexpr char kKind[] = "rollout_replay";
constexpr int64_t kFormat = 1;
constexpr char kStates[] = "states";
// Deflate halves a tabletop replay (much of a state stands still: plate, bowl, the toast before
// the grasp). Measured on 20 tabletop rollouts (993 kB raw): level 1 gives 437 kB, level 9
// 434 kB in nearly three times as long; byte shuffling made it larger (458 kB), so it is off.
constexpr unsigned kDeflateLevel = 1;

/// Writes a (rows, cols) float64 matrix as one chunk, gzipped (when this HDF5 has zlib) and
/// checksummed. The h5 wrapper writes only contiguous datasets.
void WriteStates(const h5::File& file, hid_t group, const std::string& group_name,
                 const std::vector<std::vector<double>>& states, hsize_t cols) {
  const std::string name = group_name + "/" + kStates;
  const hsize_t dims[2] = {states.size(), cols};
  std::vector<double> values;
  values.reserve(dims[0] * dims[1]);
  for (const std::vector<double>& state : states) {
    values.insert(values.end(), state.begin(), state.end());
  }
  const h5::Handle space(H5Screate_simple(2, dims, nullptr));
  const h5::Handle properties(H5Pcreate(H5P_DATASET_CREATE));
  if (H5Pset_chunk(properties.id(), 2, dims) < 0 ||
      (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0 &&
       H5Pset_deflate(properties.id(), kDeflateLevel) < 0) ||
      H5Pset_fletcher32(properties.id()) < 0) {
    h5::Fail(file.path(), "cannot set up the filters of dataset '" + name + "'");
  }
  const h5::Handle dataset(H5Dcreate2(group, kStates, H5T_IEEE_F64LE, space.id(), H5P_DEFAULT,
                                      properties.id(), H5P_DEFAULT));
  if (!dataset.valid() ||
      H5Dwrite(dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    h5::Fail(file.path(), "cannot write dataset '" + name + "'");
  }
}

/// Reads `group_name`/states, which must be (T >= 1, state_size), as doubles.
std::vector<std::vector<double>> ReadStates(const h5::File& file, const std::string& group_name,
                                            int state_size) {
  // Addressed from the root so that the wrapper's messages name the scenario too.
  const std::string name = group_name + "/" + kStates;
  const std::vector<hsize_t> dims = h5::Dimensions(file, file.id(), name);
  if (dims.size() != 2 || dims[0] < 1 || dims[1] != static_cast<hsize_t>(state_size)) {
    h5::Fail(file.path(), "dataset '" + name + "' has shape " + h5::ShapeText(dims) +
                              ", expected (steps + 1, " + std::to_string(state_size) +
                              ") with the file's state_size");
  }
  const h5::Handle dataset(H5Dopen2(file.id(), name.c_str(), H5P_DEFAULT));
  if (!dataset.valid()) h5::Fail(file.path(), "cannot open dataset '" + name + "'");
  std::vector<double> values(dims[0] * dims[1]);
  if (H5Dread(dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    h5::Fail(file.path(), "cannot read dataset '" + name + "' (corrupt or truncated file?)");
  }
  std::vector<std::vector<double>> states(dims[0]);
  for (size_t t = 0; t < states.size(); ++t) {
    states[t].assign(values.begin() + t * dims[1], values.begin() + (t + 1) * dims[1]);
  }
  return states;
}

/// Reads a count attribute of the root and checks it is in [minimum, 2^30].
int ReadCount(const h5::File& file, const std::string& name, int64_t minimum) {
  constexpr int64_t kMaximum = int64_t{1} << 30;
  const int64_t value = h5::ReadIntAttribute(file, file.id(), name);
  if (value < minimum || value > kMaximum) {
    h5::Fail(file.path(), "attribute '" + name + "' is " + std::to_string(value) + ", expected " +
                              std::to_string(minimum) + " to " + std::to_string(kMaximum));
  }
  return static_cast<int>(value);
}

void CheckReplay(const std::string& path, const RolloutReplay& replay) {
  if (replay.state_size <= 0) {
    throw UserError(path + ": a rollout replay needs a positive state size, got " +
                    std::to_string(replay.state_size));
  }
  for (size_t i = 0; i < replay.scenarios.size(); ++i) {
    const std::vector<std::vector<double>>& states = replay.scenarios[i].states;
    if (states.empty()) {
      throw UserError(path + ": scenario " + std::to_string(i) + " of the replay has no states");
    }
    for (size_t t = 0; t < states.size(); ++t) {
      if (states[t].size() != static_cast<size_t>(replay.state_size)) {
        throw UserError(path + ": scenario " + std::to_string(i) + " state " + std::to_string(t) +
                        " has " + std::to_string(states[t].size()) +
                        " values, the replay's state size is " + std::to_string(replay.state_size));
      }
    }
  }
}

}  // namespace

std::string ScenarioGroupName(int index) { return "scenario_" + std::to_string(index); }

void WriteRolloutReplay(const std::string& path, const RolloutReplay& replay) {
  CheckReplay(path, replay);
  WriteFileVia(path, Durability::kFsync, [&](const std::string& tmp) {
    h5::File file = h5::File::Create(tmp);
    const hid_t root = file.id();
    h5::WriteAttribute(file, root, "recon_kind", std::string(kKind));
    h5::WriteAttribute(file, root, "recon_format", kFormat);
    h5::WriteAttribute(file, root, "world", replay.world);
    h5::WriteAttribute(file, root, "method", replay.method);
    h5::WriteAttribute(file, root, "state_size", static_cast<int64_t>(replay.state_size));
    h5::WriteAttribute(file, root, "num_scenarios", static_cast<int64_t>(replay.scenarios.size()));
    for (size_t i = 0; i < replay.scenarios.size(); ++i) {
      const ScenarioReplay& scenario = replay.scenarios[i];
      const h5::Handle group = h5::CreateGroup(file, root, ScenarioGroupName(static_cast<int>(i)));
      h5::WriteAttribute(file, group.id(), "seed", static_cast<int64_t>(scenario.seed));
      h5::WriteAttribute(file, group.id(), "metric", scenario.metric);
      h5::WriteAttribute(file, group.id(), "succeeded", static_cast<int64_t>(scenario.succeeded));
      WriteStates(file, group.id(), ScenarioGroupName(static_cast<int>(i)), scenario.states,
                  static_cast<hsize_t>(replay.state_size));
    }
    file.Close();
  });
}

RolloutReplayFile RolloutReplayFile::Open(const std::string& path) {
  RolloutReplayFile replay(h5::File::OpenReadOnly(path));
  const h5::File& file = replay.file_;
  const std::string kind = h5::ReadStringAttribute(file, file.id(), "recon_kind");
  if (kind != kKind) {
    h5::Fail(path, "attribute 'recon_kind' is \"" + kind + "\", not \"" + kKind +
                       "\": this is not a rollout replay");
  }
  const int64_t format = h5::ReadIntAttribute(file, file.id(), "recon_format");
  if (format != kFormat) {
    h5::Fail(path, "attribute 'recon_format' is " + std::to_string(format) +
                       "; this program reads rollout replays of format " + std::to_string(kFormat));
  }
  replay.world_ = h5::ReadStringAttribute(file, file.id(), "world");
  replay.method_ = h5::ReadStringAttribute(file, file.id(), "method");
  replay.state_size_ = ReadCount(file, "state_size", 1);
  replay.num_scenarios_ = ReadCount(file, "num_scenarios", 0);
  for (int i = 0; i < replay.num_scenarios_; ++i) {
    if (!h5::Exists(file.id(), ScenarioGroupName(i))) {
      h5::Fail(path, "missing group '" + ScenarioGroupName(i) + "' (num_scenarios is " +
                         std::to_string(replay.num_scenarios_) + ")");
    }
  }
  return replay;
}

ScenarioReplay RolloutReplayFile::ReadScenario(int index) const {
  if (index < 0 || index >= num_scenarios_) {
    throw std::out_of_range("rollout replay scenario " + std::to_string(index) + " of " +
                            std::to_string(num_scenarios_));
  }
  const std::string name = ScenarioGroupName(index);
  const h5::Handle group = h5::OpenGroup(file_, file_.id(), name);
  ScenarioReplay scenario;
  try {
    scenario.seed = static_cast<uint64_t>(h5::ReadIntAttribute(file_, group.id(), "seed"));
    scenario.metric = h5::ReadDoubleAttribute(file_, group.id(), "metric");
    scenario.succeeded = h5::ReadIntAttribute(file_, group.id(), "succeeded") != 0;
  } catch (const UserError& e) {
    // The wrapper names the attribute but not its group.
    throw UserError(std::string(e.what()) + " in group '" + name + "'");
  }
  scenario.states = ReadStates(file_, name, state_size_);
  return scenario;
}

RolloutReplay ReadRolloutReplay(const std::string& path) {
  const RolloutReplayFile file = RolloutReplayFile::Open(path);
  RolloutReplay replay;
  replay.world = file.world();
  replay.method = file.method();
  replay.state_size = file.state_size();
  replay.scenarios.reserve(static_cast<size_t>(file.NumScenarios()));
  for (int i = 0; i < file.NumScenarios(); ++i) replay.scenarios.push_back(file.ReadScenario(i));
  return replay;
}

}  // namespace recon::store
