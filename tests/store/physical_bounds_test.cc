// A value no robot of the session's cell could record (a joint angle of 1e6 rad, a beacon read in
// millimetres) is finite, so only the world's physical bounds catch it: on commit, on reading a
// file that was edited afterwards, and on importing an edited export.

#include "engine/worlds/physical_bounds.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/store/h5.h"
#include "engine/store/robomimic_io.h"
#include "engine/store/session.h"
#include "tests/store/store_test_support.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::TempDir;

// The shapes of a tabletop-state session: x = 6 joint angles + gripper opening, y = toast,
// plate and bowl (x, y), b = the plate beacon's (x, y), u = 6 joint velocities + gripper.
SessionManifest TabletopStateManifest() {
  SessionManifest m = testing::SmallManifest("float32");
  m.world = "tabletop-state";
  m.beacons = {{"plate", "the plate", "position", 2, "m"}};
  m.spec.x_dim = 7;
  m.spec.y_shape = {6};
  m.spec.b_dim = 2;
  m.spec.u_dim = 7;
  return m;
}

// Shapes with a vector y of `y` values.
DataSpec Spec(int x, int64_t y, int b, int u) {
  DataSpec spec;
  spec.x_dim = x;
  spec.y_shape = {y};
  spec.b_dim = b;
  spec.u_dim = u;
  return spec;
}

// Values a UR5 in the cell records, from `seed`; the last sample sits on every limit.
DemoRecord ArmDemo(int n, uint64_t seed) {
  Rng rng(seed);
  DemoRecord record;
  record.meta.seed = seed;
  record.meta.source = "bounds test";
  record.meta.teaching_seconds = 0.1 * n;
  for (int i = 0; i < n; ++i) {
    Sample s;
    for (int j = 0; j < 6; ++j) s.x.push_back(static_cast<float>(rng.Uniform(-3, 3)));
    s.x.push_back(1.0f);
    for (int k = 0; k < 6; ++k) s.y.push_back(static_cast<float>(rng.Uniform(-0.7, 0.7)));
    s.b = {static_cast<float>(rng.Uniform(0.4, 0.7)), static_cast<float>(rng.Uniform(-0.4, 0.4))};
    for (int j = 0; j < 6; ++j) s.u.push_back(static_cast<float>(rng.Uniform(-0.3, 0.3)));
    s.u.push_back(0.0f);
    record.episode.samples.push_back(s);
    record.rewards.push_back(0.0);
  }
  Sample& edge = record.episode.samples.back();
  edge.x = {6.2832f, -6.2832f, 3.1416f, 0.0f, 0.0f, 0.0f, 0.0f};
  edge.u = {static_cast<float>(M_PI), static_cast<float>(-M_PI), 0, 0, 0, 0, 1.0f};
  return record;
}

// Overwrites one value of a float dataset in place, as a person editing the file would; HDF5
// recomputes the chunk's checksum, so the file stays valid.
void EditValue(const std::string& path, const std::string& dataset, size_t index, float value) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0) << path;
  const hid_t data = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  ASSERT_GE(data, 0) << dataset;
  const hid_t space = H5Dget_space(data);
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  std::vector<float> values(static_cast<size_t>(count));
  ASSERT_GE(H5Dread(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  values.at(index) = value;
  ASSERT_GE(H5Dwrite(data, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Sclose(space);
  H5Dclose(data);
  H5Fclose(file);
}

TEST(PhysicalBoundsTest, TheArmWorldsBoundEveryFieldAndTheAbstractWorldsNone) {
  const ValueBounds tabletop =
      worlds::PhysicalBounds("tabletop-state", TabletopStateManifest().spec);
  ASSERT_EQ(tabletop.x.size(), 7u);
  ASSERT_EQ(tabletop.u.size(), 7u);
  EXPECT_EQ(tabletop.y.size(), 6u);
  EXPECT_EQ(tabletop.b.size(), 2u);
  EXPECT_DOUBLE_EQ(tabletop.x[6].lo, 0.0);
  EXPECT_DOUBLE_EQ(tabletop.x[6].hi, 1.0);
  EXPECT_GT(tabletop.x[0].hi, 2 * M_PI);
  EXPECT_GT(tabletop.u[0].hi, M_PI);
  EXPECT_LT(tabletop.u[0].hi, M_PI + 0.01);

  DataSpec camera = TabletopStateManifest().spec;
  camera.y_shape = {3, 64, 64};
  EXPECT_TRUE(worlds::PhysicalBounds("tabletop", camera).y.empty());  // pixels: uint8 checks
  EXPECT_EQ(worlds::PhysicalBounds("tabletop", camera).x.size(), 7u);

  const DataSpec bins = Spec(6, 12, 1, 6);
  EXPECT_EQ(worlds::PhysicalBounds("bintransfer", bins).u.size(), 6u);
  EXPECT_EQ(worlds::PhysicalBounds("bintransfer", bins).b.size(), 1u);

  const DataSpec plane = Spec(2, 6, 2, 2);
  EXPECT_TRUE(worlds::PhysicalBounds("dynamic2d", plane).empty());
  EXPECT_TRUE(worlds::PhysicalBounds("imported", plane).empty());
  // Another world's shapes under this name: the shape check names that, not the bounds.
  EXPECT_TRUE(worlds::PhysicalBounds("tabletop", plane).empty());
}

TEST(PhysicalBoundsTest, ValuesAtTheLimitsAreKept) {
  TempDir dir("bounds-edge");
  Session session = Session::Create(dir.Path("s"), TabletopStateManifest());
  const DemoRecord demo = ArmDemo(6, 1);
  session.CommitDemo(demo);
  EXPECT_EQ(session.ReadDemo("demo_0").episode.samples.back().x, demo.episode.samples.back().x);
}

TEST(PhysicalBoundsTest, ACommitOutsideThePhysicalRangeIsRefusedNamingSampleFieldAndDimension) {
  struct Case {
    const char* field;
    int dimension;
    float value;
    const char* expected;
  };
  const Case cases[] = {
      {"x", 1, 1e6f,
       "sample 3 field 'x' dimension 1 (joint 1 angle (rad)) is 1e+06, outside the physical "
       "range -6.2932 to 6.2932"},
      {"x", 6, -0.5f, "sample 3 field 'x' dimension 6 (gripper opening (0 shut, 1 open)) is -0.5"},
      {"u", 2, 4.0f, "sample 3 field 'u' dimension 2 (joint 2 velocity command (rad/s)) is 4"},
      {"u", 6, 2.0f, "sample 3 field 'u' dimension 6 (gripper command (0 open, 1 close)) is 2"},
      // A beacon read in millimetres instead of metres.
      {"b", 0, 560.0f, "sample 3 field 'b' dimension 0 (beacon reading (m)) is 560"},
      {"y", 5, -1e9f, "sample 3 field 'y' dimension 5 (object coordinate (m)) is -1e+09"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.field) + " " + std::to_string(c.dimension));
    TempDir dir("bounds-commit");
    Session session = Session::Create(dir.Path("s"), TabletopStateManifest());
    session.CommitDemo(ArmDemo(5, 1));
    DemoRecord bad = ArmDemo(5, 2);
    Sample& s = bad.episode.samples[3];
    std::vector<float>& field = c.field[0] == 'x'   ? s.x
                                : c.field[0] == 'u' ? s.u
                                : c.field[0] == 'b' ? s.b
                                                    : s.y;
    field[c.dimension] = c.value;
    const std::string error = ErrorOf([&] { session.CommitDemo(bad); });
    EXPECT_THAT(error, HasSubstr(c.expected));
    EXPECT_THAT(error, HasSubstr("demo_1"));
    ASSERT_EQ(session.demos().size(), 1u);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.Path("s/episodes")), {}), 1);
    // The play path is checked the same way.
    PlayRecord play;
    play.meta.seed = 3;
    play.meta.source = "bounds test";
    for (const Sample& row : bad.episode.samples) play.samples.push_back({row.x, row.y, row.b});
    if (c.field[0] != 'u') {
      EXPECT_THAT(ErrorOf([&] { session.CommitPlay(play); }), HasSubstr(c.expected));
      EXPECT_TRUE(session.play_chunks().empty());
    }
  }
}

TEST(PhysicalBoundsTest, AnEpisodeEditedAfterRecordingIsRefusedWhenRead) {
  TempDir dir("bounds-read");
  {
    Session session = Session::Create(dir.Path("s"), TabletopStateManifest());
    session.CommitDemo(ArmDemo(5, 1));
    session.CommitDemo(ArmDemo(5, 2));
  }
  const std::string path = Session::Open(dir.Path("s")).Find("demo_1").path;
  EditValue(path, "obs/robot_state", 2 * 7 + 4, 1e6f);  // sample 2, joint 4
  const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  const std::string error = ErrorOf([&] { session.ReadDemo("demo_1"); });
  EXPECT_THAT(error, HasSubstr(path + ": sample 2 field 'x' dimension 4 (joint 4 angle (rad)) "
                                      "is 1e+06"));
  EXPECT_THAT(ErrorOf([&] { session.LoadDataset(); }), HasSubstr("sample 2 field 'x'"));
  EXPECT_NO_THROW(session.ReadDemo("demo_0"));
}

TEST(PhysicalBoundsTest, AnEditedExportIsRefusedByTheImportAndCreatesNothing) {
  TempDir dir("bounds-import");
  {
    Session session = Session::Create(dir.Path("s"), TabletopStateManifest());
    session.CommitDemo(ArmDemo(5, 1));
    session.CommitDemo(ArmDemo(5, 2));
    ExportRobomimic(session, dir.Path("out.hdf5"));
  }
  ImportRobomimic(dir.Path("out.hdf5"), dir.Path("copy"));  // the untouched export imports
  EditValue(dir.Path("out.hdf5"), "data/demo_1/actions", 4 * 7 + 0, -50.0f);
  const std::string error =
      ErrorOf([&] { ImportRobomimic(dir.Path("out.hdf5"), dir.Path("edited")); });
  EXPECT_THAT(error, HasSubstr("out.hdf5"));
  EXPECT_THAT(error, HasSubstr("sample 4 field 'u' dimension 0 (joint 0 velocity command "
                               "(rad/s)) is -50"));
  EXPECT_FALSE(fs::exists(dir.Path("edited")));
}

}  // namespace
}  // namespace recon::store
