#include "engine/store/rollout_replay.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/store/h5.h"
#include "tests/store/store_test_support.h"
#include "tests/support/run_command.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::TempDir;

constexpr int kStateSize = 5;

/// Three scenarios of 4, 1 and 7 states whose values follow from `seed`; the last seed uses all
/// 64 bits (test seeds come from Rng::Derive).
RolloutReplay SyntheticReplay(uint64_t seed) {
  Rng rng(seed);
  RolloutReplay replay;
  replay.world = "tabletop";
  replay.method = "recon";
  replay.state_size = kStateSize;
  const std::vector<uint64_t> seeds = {3, 0, 0xfedcba9876543210ULL};
  const std::vector<int> lengths = {4, 1, 7};
  for (size_t i = 0; i < seeds.size(); ++i) {
    ScenarioReplay scenario;
    scenario.seed = seeds[i];
    scenario.metric = rng.Uniform(0, 1);
    scenario.succeeded = i % 2 == 0;
    for (int t = 0; t < lengths[i]; ++t) {
      std::vector<double> state;
      for (int k = 0; k < kStateSize; ++k) state.push_back(rng.Uniform(-4, 4));
      scenario.states.push_back(state);
    }
    replay.scenarios.push_back(scenario);
  }
  return replay;
}

void ExpectSameScenario(const ScenarioReplay& actual, const ScenarioReplay& expected) {
  EXPECT_EQ(actual.seed, expected.seed);
  EXPECT_EQ(actual.metric, expected.metric);  // bit for bit: float64 on disk
  EXPECT_EQ(actual.succeeded, expected.succeeded);
  EXPECT_EQ(actual.states, expected.states);
}

std::vector<std::string> FilesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  return names;
}

/// A written file opened for editing, to damage it in one precise way.
class EditableFile {
 public:
  explicit EditableFile(const std::string& path)
      : handle_(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {
    EXPECT_TRUE(handle_.valid()) << path;
  }
  hid_t id() const { return handle_.id(); }

 private:
  h5::Handle handle_;
};

void SetIntAttribute(hid_t location, const char* name, int64_t value) {
  const h5::Handle space(H5Screate(H5S_SCALAR));
  const h5::Handle attribute(
      H5Acreate2(location, name, H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT));
  ASSERT_TRUE(attribute.valid());
  ASSERT_GE(H5Awrite(attribute.id(), H5T_NATIVE_INT64, &value), 0);
}

void SetStringAttribute(hid_t location, const char* name, const std::string& value) {
  const h5::Handle type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type.id(), value.size());
  const h5::Handle space(H5Screate(H5S_SCALAR));
  const h5::Handle attribute(
      H5Acreate2(location, name, type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT));
  ASSERT_TRUE(attribute.valid());
  ASSERT_GE(H5Awrite(attribute.id(), type.id(), value.data()), 0);
}

void WriteZeros(hid_t location, const char* name, const std::vector<hsize_t>& dims) {
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  const std::vector<double> zeros(count, 0.0);
  const h5::Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  const h5::Handle dataset(H5Dcreate2(location, name, H5T_IEEE_F64LE, space.id(), H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT));
  ASSERT_TRUE(dataset.valid());
  ASSERT_GE(H5Dwrite(dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data()),
            0);
}

TEST(RolloutReplayTest, RoundTripKeepsEveryValue) {
  TempDir dir("replay-round-trip");
  const std::string path = dir.Path("recon.replay.h5");
  const RolloutReplay written = SyntheticReplay(1);
  WriteRolloutReplay(path, written);
  const RolloutReplay read = ReadRolloutReplay(path);
  EXPECT_EQ(read.world, "tabletop");
  EXPECT_EQ(read.method, "recon");
  EXPECT_EQ(read.state_size, kStateSize);
  ASSERT_EQ(read.scenarios.size(), written.scenarios.size());
  for (size_t i = 0; i < read.scenarios.size(); ++i) {
    SCOPED_TRACE("scenario " + std::to_string(i));
    ExpectSameScenario(read.scenarios[i], written.scenarios[i]);
  }
  // Only the file: the temporary it was written through is gone.
  EXPECT_EQ(FilesIn(dir.Path()), std::vector<std::string>{"recon.replay.h5"});

  // Writing again replaces the file whole.
  const RolloutReplay other = SyntheticReplay(2);
  WriteRolloutReplay(path, other);
  ExpectSameScenario(ReadRolloutReplay(path).scenarios[2], other.scenarios[2]);
}

TEST(RolloutReplayTest, OpenFileReadsOneScenarioAtATime) {
  TempDir dir("replay-lazy");
  const std::string path = dir.Path("baseline.replay.h5");
  RolloutReplay written = SyntheticReplay(3);
  written.method = "baseline";
  WriteRolloutReplay(path, written);
  const RolloutReplayFile file = RolloutReplayFile::Open(path);
  EXPECT_EQ(file.path(), path);
  EXPECT_EQ(file.world(), "tabletop");
  EXPECT_EQ(file.method(), "baseline");
  EXPECT_EQ(file.state_size(), kStateSize);
  ASSERT_EQ(file.NumScenarios(), 3);
  ExpectSameScenario(file.ReadScenario(2), written.scenarios[2]);
  ExpectSameScenario(file.ReadScenario(0), written.scenarios[0]);
  EXPECT_THROW(file.ReadScenario(3), std::out_of_range);
  EXPECT_THROW(file.ReadScenario(-1), std::out_of_range);
}

TEST(RolloutReplayTest, StatesAreCompressedAndChecksummedAsHdf5ToolsSeeThem) {
  TempDir dir("replay-layout");
  const std::string path = dir.Path("r.replay.h5");
  WriteRolloutReplay(path, SyntheticReplay(4));
  const recon::testing::CommandResult result =
      recon::testing::RunCommand(std::string(H5DUMP) + " -H -p -d /scenario_2/states " + path);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("H5T_IEEE_F64LE"));
  EXPECT_THAT(result.output, HasSubstr("( 7, 5 )"));
  EXPECT_THAT(result.output, HasSubstr("DEFLATE"));
  EXPECT_THAT(result.output, HasSubstr("FLETCHER32"));
}

TEST(RolloutReplayTest, EmptyReplayRoundTrips) {
  TempDir dir("replay-empty");
  RolloutReplay empty;
  empty.world = "tabletop";
  empty.method = "recon";
  empty.state_size = 29;
  WriteRolloutReplay(dir.Path("e.h5"), empty);
  const RolloutReplay read = ReadRolloutReplay(dir.Path("e.h5"));
  EXPECT_EQ(read.state_size, 29);
  EXPECT_TRUE(read.scenarios.empty());
}

TEST(RolloutReplayTest, WrongShapesAreRefusedBeforeAnythingIsWritten) {
  TempDir dir("replay-write-shapes");
  const std::string path = dir.Path("r.h5");
  RolloutReplay replay = SyntheticReplay(5);
  replay.scenarios[1].states.push_back(std::vector<double>(kStateSize - 1, 0.0));
  std::string error = ErrorOf([&] { WriteRolloutReplay(path, replay); });
  EXPECT_THAT(error, HasSubstr(path));
  EXPECT_THAT(error, HasSubstr("scenario 1 state 1 has 4 values"));
  EXPECT_THAT(error, HasSubstr("state size is 5"));

  replay = SyntheticReplay(5);
  replay.scenarios[2].states.clear();
  EXPECT_THAT(ErrorOf([&] { WriteRolloutReplay(path, replay); }),
              HasSubstr("scenario 2 of the replay has no states"));
  replay = SyntheticReplay(5);
  replay.state_size = 0;
  EXPECT_THAT(ErrorOf([&] { WriteRolloutReplay(path, replay); }), HasSubstr("positive state size"));
  EXPECT_TRUE(FilesIn(dir.Path()).empty());
}

TEST(RolloutReplayTest, MissingTruncatedOrForeignFilesNameTheFile) {
  TempDir dir("replay-bad-files");
  const std::string missing = dir.Path("missing.replay.h5");
  EXPECT_THAT(ErrorOf([&] { ReadRolloutReplay(missing); }), HasSubstr(missing));

  const std::string text = dir.Path("text.replay.h5");
  std::ofstream(text) << "not an HDF5 file\n";
  EXPECT_THAT(ErrorOf([&] { RolloutReplayFile::Open(text); }), HasSubstr(text));

  const std::string truncated = dir.Path("truncated.replay.h5");
  WriteRolloutReplay(truncated, SyntheticReplay(6));
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  const std::string error = ErrorOf([&] { ReadRolloutReplay(truncated); });
  EXPECT_THAT(error, HasSubstr(truncated));
  EXPECT_THAT(error, HasSubstr("truncated"));
}

TEST(RolloutReplayTest, DamagedStatesNameTheDataset) {
  TempDir dir("replay-corrupt");
  const std::string path = dir.Path("r.replay.h5");
  WriteRolloutReplay(path, SyntheticReplay(7));
  // Where scenario 1's (single) chunk lies in the file.
  haddr_t address = 0;
  hsize_t size = 0;
  {
    EditableFile file(path);
    const h5::Handle dataset(H5Dopen2(file.id(), "scenario_1/states", H5P_DEFAULT));
    ASSERT_TRUE(dataset.valid());
    const hsize_t origin[2] = {0, 0};
    unsigned filter_mask = 0;
    ASSERT_GE(H5Dget_chunk_info_by_coord(dataset.id(), origin, &filter_mask, &address, &size), 0);
    ASSERT_GT(size, 8u);
  }
  {
    std::fstream bytes(path, std::ios::in | std::ios::out | std::ios::binary);
    bytes.seekp(static_cast<std::streamoff>(address + size / 2));
    const char garbage[4] = {'\x5a', '\xa5', '\x5a', '\xa5'};
    bytes.write(garbage, sizeof(garbage));
  }
  const RolloutReplayFile file = RolloutReplayFile::Open(path);  // the root is intact
  ExpectSameScenario(file.ReadScenario(0), SyntheticReplay(7).scenarios[0]);
  const std::string error = ErrorOf([&] { file.ReadScenario(1); });
  EXPECT_THAT(error, HasSubstr(path));
  EXPECT_THAT(error, HasSubstr("dataset 'scenario_1/states'"));
}

TEST(RolloutReplayTest, WrongAttributesAndShapesNameWhatIsWrong) {
  TempDir dir("replay-wrong");
  const std::string path = dir.Path("r.replay.h5");
  const auto fresh = [&] { WriteRolloutReplay(path, SyntheticReplay(8)); };

  fresh();
  {
    EditableFile file(path);
    ASSERT_GE(H5Adelete(file.id(), "recon_kind"), 0);
    SetStringAttribute(file.id(), "recon_kind", "demo");
  }
  EXPECT_THAT(ErrorOf([&] { ReadRolloutReplay(path); }),
              HasSubstr("attribute 'recon_kind' is \"demo\""));

  fresh();
  {
    EditableFile file(path);
    ASSERT_GE(H5Adelete(file.id(), "state_size"), 0);
  }
  std::string error = ErrorOf([&] { ReadRolloutReplay(path); });
  EXPECT_THAT(error, HasSubstr(path));
  EXPECT_THAT(error, HasSubstr("missing attribute 'state_size'"));

  fresh();
  {
    EditableFile file(path);
    ASSERT_GE(H5Adelete(file.id(), "num_scenarios"), 0);
    SetIntAttribute(file.id(), "num_scenarios", 4);
  }
  EXPECT_THAT(ErrorOf([&] { RolloutReplayFile::Open(path); }),
              HasSubstr("missing group 'scenario_3'"));

  fresh();
  {
    EditableFile file(path);
    ASSERT_GE(H5Adelete_by_name(file.id(), "scenario_1", "seed", H5P_DEFAULT), 0);
  }
  error = ErrorOf([&] { RolloutReplayFile::Open(path).ReadScenario(1); });
  EXPECT_THAT(error, HasSubstr("missing attribute 'seed'"));
  EXPECT_THAT(error, HasSubstr("scenario_1"));

  // A states dataset one column short, and one of rank 1.
  for (const std::vector<hsize_t>& dims :
       {std::vector<hsize_t>{4, kStateSize - 1}, std::vector<hsize_t>{4 * kStateSize}}) {
    fresh();
    {
      EditableFile file(path);
      ASSERT_GE(H5Ldelete(file.id(), "scenario_0/states", H5P_DEFAULT), 0);
      WriteZeros(file.id(), "scenario_0/states", dims);
    }
    error = ErrorOf([&] { ReadRolloutReplay(path); });
    EXPECT_THAT(error, HasSubstr(path));
    EXPECT_THAT(error, HasSubstr("dataset 'scenario_0/states' has shape"));
    EXPECT_THAT(error, HasSubstr(", 5)"));
  }
}

}  // namespace
}  // namespace recon::store
