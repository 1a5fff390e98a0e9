#include "engine/store/robomimic_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/store/h5.h"
#include "tests/store/store_test_support.h"
#include "tests/support/run_command.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::SmallManifest;
using testing::SyntheticDemo;
using testing::SyntheticPlay;
using testing::TempDir;

/// Output of an HDF5 command-line tool (what a user would run to look at the file).
std::string Tool(const std::string& command) {
  const recon::testing::CommandResult result = recon::testing::RunCommand(command);
  EXPECT_EQ(result.exit_code, 0) << command << "\n" << result.output;
  return result.output;
}

/// demo_0 (3 samples), demo_1 (4, bad), demo_2 (5, valid) and two play chunks.
void MakeSession(const std::string& dir) {
  Session session = Session::Create(dir, SmallManifest());
  session.CommitDemo(SyntheticDemo(3, 1));
  session.CommitDemo(SyntheticDemo(4, 2));
  session.CommitDemo(SyntheticDemo(5, 3));
  session.CommitPlay(SyntheticPlay(2, 4));
  session.CommitPlay(SyntheticPlay(3, 5));
  session.MarkBad("demo_1", true);
  session.SetSplit("demo_2", "valid");
  session.SetNote("demo_2", "the gripper slipped");
}

TEST(RobomimicTest, ExportHasRobomimicsLayoutAsHdf5ToolsSeeIt) {
  TempDir dir("export-layout");
  MakeSession(dir.Path("s"));
  const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  const ExportSummary summary = ExportRobomimic(session, dir.Path("out.hdf5"));
  EXPECT_EQ(summary.demos, 2);
  EXPECT_EQ(summary.samples, 8);
  EXPECT_EQ(summary.play_samples, 5);

  // h5ls pads names into columns; compare with runs of spaces squeezed to one.
  std::string listing = Tool(std::string(H5LS) + " -r " + dir.Path("out.hdf5"));
  listing.erase(std::unique(listing.begin(), listing.end(),
                            [](char a, char b) { return a == ' ' && b == ' '; }),
                listing.end());
  for (const char* line :
       {"/data/demo_0/actions Dataset {3, 2}", "/data/demo_0/dones Dataset {3}",
        "/data/demo_0/rewards Dataset {3}", "/data/demo_0/states Dataset {3, 2}",
        "/data/demo_0/obs/camera_image Dataset {3, 4, 5, 3}",
        "/data/demo_0/obs/robot_state Dataset {3, 2}", "/data/demo_0/obs/beacon_red Dataset {3, 2}",
        "/data/demo_0/obs/beacon_dist Dataset {3, 1}",
        "/data/demo_0/next_obs/camera_image Dataset {3, 4, 5, 3}",
        "/data/demo_2/actions Dataset {5, 2}", "/mask/train Dataset {1}", "/mask/valid Dataset {1}",
        "/play/play_1/obs/beacon_red Dataset {3, 2}"}) {
    EXPECT_THAT(listing, HasSubstr(line));
  }
  EXPECT_THAT(listing, Not(HasSubstr("demo_1")));         // bad: left out
  EXPECT_THAT(listing, Not(HasSubstr("External Link")));  // self-contained

  const std::string attributes = Tool(std::string(H5DUMP) + " -A -g /data " + dir.Path("out.hdf5"));
  EXPECT_THAT(attributes, HasSubstr("ATTRIBUTE \"total\""));
  EXPECT_THAT(attributes, HasSubstr("ATTRIBUTE \"env_args\""));
  EXPECT_THAT(attributes, HasSubstr("ATTRIBUTE \"num_samples\""));
  EXPECT_THAT(attributes, HasSubstr("recon/synthetic"));
  const std::string image_type =
      Tool(std::string(H5DUMP) + " -H -d /data/demo_0/obs/camera_image " + dir.Path("out.hdf5"));
  EXPECT_THAT(image_type, HasSubstr("H5T_STD_U8LE"));
  const std::string masks = Tool(std::string(H5DUMP) + " -d /mask/valid " + dir.Path("out.hdf5"));
  EXPECT_THAT(masks, HasSubstr("\"demo_2\""));
  // next_obs is the following step's observation; the last repeats.
  const h5::File file = h5::File::OpenReadOnly(dir.Path("out.hdf5"));
  const std::vector<float> obs = h5::ReadFloats(file, file.id(), "data/demo_2/obs/robot_state");
  const std::vector<float> next =
      h5::ReadFloats(file, file.id(), "data/demo_2/next_obs/robot_state");
  EXPECT_EQ(std::vector<float>(obs.begin() + 2, obs.end()),
            std::vector<float>(next.begin(), next.end() - 2));
  EXPECT_EQ(std::vector<float>(obs.end() - 2, obs.end()),
            std::vector<float>(next.end() - 2, next.end()));
}

TEST(RobomimicTest, ExportThenImportGivesBackTheSameSession) {
  TempDir dir("roundtrip");
  MakeSession(dir.Path("s"));
  ExportOptions options;
  options.include_bad = true;
  {
    const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
    EXPECT_EQ(ExportRobomimic(session, dir.Path("out.hdf5"), options).demos, 3);
  }
  const ImportSummary summary = ImportRobomimic(dir.Path("out.hdf5"), dir.Path("copy"));
  EXPECT_TRUE(summary.from_recon);
  EXPECT_EQ(summary.demos, 3);
  EXPECT_EQ(summary.play_samples, 5);
  const Session original = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  const Session copy = Session::Open(dir.Path("copy"), Session::Access::kReadOnly);
  EXPECT_EQ(copy.manifest().spec, original.manifest().spec);
  EXPECT_EQ(copy.manifest().beacons, original.manifest().beacons);
  EXPECT_EQ(copy.Find("demo_2").flags.split, "valid");
  EXPECT_EQ(copy.Find("demo_2").flags.note, "the gripper slipped");
  EXPECT_TRUE(copy.Find("demo_1").flags.bad);
  EXPECT_FALSE(copy.Find("demo_0").flags.bad);
  const Dataset a = original.LoadDataset({Split::kAll, true, true});
  const Dataset b = copy.LoadDataset({Split::kAll, true, true});
  ASSERT_EQ(a.demos.size(), b.demos.size());
  for (size_t i = 0; i < a.demos.size(); ++i) {
    ASSERT_EQ(a.demos[i].samples.size(), b.demos[i].samples.size());
    for (size_t t = 0; t < a.demos[i].samples.size(); ++t) {
      EXPECT_EQ(a.demos[i].samples[t].y, b.demos[i].samples[t].y);
      EXPECT_EQ(a.demos[i].samples[t].b, b.demos[i].samples[t].b);
      EXPECT_EQ(a.demos[i].samples[t].u, b.demos[i].samples[t].u);
    }
  }
  EXPECT_EQ(Fingerprint(a), Fingerprint(b));
  EXPECT_EQ(copy.Find("demo_0").meta.seed, original.Find("demo_0").meta.seed);
}

TEST(RobomimicTest, AnImportSweepsTheStagingFolderOfAKilledImport) {
  TempDir dir("staging");
  MakeSession(dir.Path("s"));
  {
    const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
    ExportRobomimic(session, dir.Path("out.hdf5"));
  }
  // What `session import` leaves when killed half-way: its staging folder, named by its pid.
  const pid_t killed = fork();
  if (killed == 0) _exit(0);
  int status = 0;
  waitpid(killed, &status, 0);
  const std::string left = dir.Path("copy.importing." + std::to_string(killed));
  fs::create_directories(left + "/episodes");
  std::ofstream(left + "/episodes/demo_0.h5") << "half an episode";
  ImportRobomimic(dir.Path("out.hdf5"), dir.Path("copy"));
  EXPECT_FALSE(fs::exists(left));
  EXPECT_EQ(Session::Open(dir.Path("copy"), Session::Access::kReadOnly).demos().size(), 2u);
}

TEST(RobomimicTest, ImportKeepsTheOrderOfManyPlayChunksAndRenumbersGaps) {
  TempDir dir("many-chunks");
  {
    Session session = Session::Create(dir.Path("s"), SmallManifest());
    for (int i = 0; i < 4; ++i) session.CommitDemo(SyntheticDemo(2, 100 + i));
    for (int i = 0; i < 12; ++i) session.CommitPlay(SyntheticPlay(1, 200 + i));
    session.DeleteEpisode("demo_1");  // the export has demo_0, demo_2, demo_3
    ExportRobomimic(session, dir.Path("out.hdf5"));
  }
  ImportRobomimic(dir.Path("out.hdf5"), dir.Path("copy"));
  const Session original = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  const Session copy = Session::Open(dir.Path("copy"), Session::Access::kReadOnly);
  ASSERT_EQ(copy.demos().size(), 3u);
  EXPECT_EQ(copy.demos()[1].name, "demo_1");
  EXPECT_EQ(copy.demos()[1].meta.seed, original.Find("demo_2").meta.seed);
  const Dataset a = original.LoadDataset({Split::kAll, true, true});
  const Dataset b = copy.LoadDataset({Split::kAll, true, true});
  ASSERT_EQ(a.play.size(), 12u);
  ASSERT_EQ(b.play.size(), 12u);
  for (size_t i = 0; i < a.play.size(); ++i) EXPECT_EQ(a.play[i].b, b.play[i].b) << "chunk " << i;
  EXPECT_THAT(ErrorOf([&] { ImportRobomimic(dir.Path("out.hdf5"), dir.Path("s")); }),
              HasSubstr("already holds a teaching session"));
}

/// A robomimic file as robosuite's tools write it: float64 low-dim keys and actions, uint8
/// images, no RECON attributes.
void WriteForeignFile(const std::string& path, int bad_demo = -1) {
  h5::File file = h5::File::Create(path);
  const h5::Handle data = h5::CreateGroup(file, file.id(), "data");
  h5::WriteAttribute(file, data.id(), "env_args", std::string("{\"env_name\": \"Lift\"}"));
  int64_t total = 0;
  for (int d = 0; d < 2; ++d) {
    const hsize_t n = 3 + d;
    const h5::Handle demo = h5::CreateGroup(file, data.id(), "demo_" + std::to_string(d));
    h5::WriteAttribute(file, demo.id(), "num_samples", static_cast<int64_t>(n));
    const h5::Handle obs = h5::CreateGroup(file, demo.id(), "obs");
    std::vector<double> eef(n * 3), gripper(n * 2), object(n * (d == bad_demo ? 5 : 4)),
        actions(n * 7);
    for (size_t i = 0; i < eef.size(); ++i) eef[i] = 0.1 * i + d;
    for (size_t i = 0; i < gripper.size(); ++i) gripper[i] = -0.5 * i;
    for (size_t i = 0; i < object.size(); ++i) object[i] = 2.0 + i;
    for (size_t i = 0; i < actions.size(); ++i) actions[i] = 0.01 * i;
    std::vector<uint8_t> image(n * 6 * 8 * 3);
    for (size_t i = 0; i < image.size(); ++i) image[i] = static_cast<uint8_t>(i % 251);
    h5::WriteArray(file, obs.id(), "robot0_eef_pos", h5::ElementType::kFloat64, {n, 3}, eef.data());
    h5::WriteArray(file, obs.id(), "robot0_gripper_qpos", h5::ElementType::kFloat64, {n, 2},
                   gripper.data());
    h5::WriteArray(file, obs.id(), "object", h5::ElementType::kFloat64,
                   {n, static_cast<hsize_t>(d == bad_demo ? 5 : 4)}, object.data());
    h5::WriteArray(file, obs.id(), "agentview_image", h5::ElementType::kUInt8, {n, 6, 8, 3},
                   image.data());
    h5::WriteArray(file, demo.id(), "actions", h5::ElementType::kFloat64, {n, 7}, actions.data());
    total += static_cast<int64_t>(n);
  }
  h5::WriteAttribute(file, data.id(), "total", total);
  const h5::Handle mask = h5::CreateGroup(file, file.id(), "mask");
  h5::WriteStrings(file, mask.id(), "valid", {"demo_1"});
  file.Close();
}

TEST(RobomimicTest, ImportsAForeignFileThroughAKeyMapping) {
  TempDir dir("foreign");
  WriteForeignFile(dir.Path("lift.hdf5"));
  ImportMapping mapping;
  mapping.x_keys = {"robot0_eef_pos", "robot0_gripper_qpos"};
  mapping.y_key = "agentview_image";
  mapping.beacon_keys = {"object"};
  const ImportSummary summary = ImportRobomimic(dir.Path("lift.hdf5"), dir.Path("s"), mapping);
  EXPECT_FALSE(summary.from_recon);
  EXPECT_EQ(summary.demos, 2);
  EXPECT_EQ(summary.samples, 7);
  const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  const SessionManifest& m = session.manifest();
  EXPECT_EQ(m.spec.x_dim, 5);
  EXPECT_EQ(m.spec.y_shape, (std::vector<int64_t>{3, 6, 8}));
  EXPECT_EQ(m.spec.b_dim, 4);
  EXPECT_EQ(m.spec.u_dim, 7);
  EXPECT_EQ(m.y_encoding, "uint8");
  ASSERT_EQ(m.beacons.size(), 1u);
  EXPECT_EQ(m.beacons[0].name, "object");
  EXPECT_EQ(session.Find("demo_1").flags.split, "valid");
  const DemoRecord demo = session.ReadDemo("demo_1");
  ASSERT_EQ(demo.episode.samples.size(), 4u);
  const Sample& s = demo.episode.samples[2];
  EXPECT_FLOAT_EQ(s.x[0], 0.1f * 6 + 1);  // eef row 2, column 0
  EXPECT_FLOAT_EQ(s.x[3], -0.5f * 4);     // gripper row 2, column 0
  EXPECT_FLOAT_EQ(s.b[1], 2.0f + 9);      // object row 2, column 1
  EXPECT_FLOAT_EQ(s.u[6], 0.01f * 20);    // actions row 2, column 6
  // Pixel (row 1, column 2, channel 1) of frame 2, HWC in the file, CHW in memory.
  const size_t hwc = ((2 * 6 + 1) * 8 + 2) * 3 + 1;
  EXPECT_FLOAT_EQ(s.y[1 * 48 + 1 * 8 + 2], static_cast<float>(hwc % 251));
}

TEST(RobomimicTest, AForeignFileWithoutAMappingListsItsKeys) {
  TempDir dir("no-mapping");
  WriteForeignFile(dir.Path("lift.hdf5"));
  const std::string error = ErrorOf([&] { ImportRobomimic(dir.Path("lift.hdf5"), dir.Path("s")); });
  EXPECT_THAT(error, HasSubstr("was not written by RECON Studio"));
  EXPECT_THAT(error, HasSubstr("agentview_image (3, 6, 8, 3) uint8"));
  EXPECT_THAT(error, HasSubstr("robot0_eef_pos (3, 3)"));
  EXPECT_FALSE(fs::exists(dir.Path("s")));
}

TEST(RobomimicTest, ABadDemonstrationStopsTheImportAndLeavesNothing) {
  TempDir dir("bad-demo");
  WriteForeignFile(dir.Path("lift.hdf5"), /*bad_demo=*/1);
  ImportMapping mapping;
  mapping.x_keys = {"robot0_eef_pos"};
  mapping.y_key = "agentview_image";
  mapping.beacon_keys = {"object"};
  const std::string error =
      ErrorOf([&] { ImportRobomimic(dir.Path("lift.hdf5"), dir.Path("s"), mapping); });
  EXPECT_THAT(error, HasSubstr("lift.hdf5: data/demo_1: obs key 'object' has shape (4, 5)"));
  EXPECT_FALSE(fs::exists(dir.Path("s")));
  for (const auto& entry : fs::directory_iterator(dir.Path())) {
    EXPECT_THAT(entry.path().string(), Not(HasSubstr("importing"))) << "staging folder left";
  }
}

TEST(RobomimicTest, TruncatedAndForeignFilesAreNamed) {
  TempDir dir("truncated");
  MakeSession(dir.Path("s"));
  {
    const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
    ExportRobomimic(session, dir.Path("out.hdf5"));
  }
  fs::resize_file(dir.Path("out.hdf5"), fs::file_size(dir.Path("out.hdf5")) / 3);
  EXPECT_THAT(ErrorOf([&] { ImportRobomimic(dir.Path("out.hdf5"), dir.Path("copy")); }),
              HasSubstr("out.hdf5"));
  EXPECT_FALSE(fs::exists(dir.Path("copy")));
  {
    std::ofstream text(dir.Path("notes.hdf5"));
    text << "not hdf5";
  }
  EXPECT_THAT(ErrorOf([&] { ImportRobomimic(dir.Path("notes.hdf5"), dir.Path("copy")); }),
              HasSubstr("notes.hdf5: cannot open as HDF5"));
}

TEST(RobomimicTest, AFailedExportNeverReplacesAGoodFile) {
  TempDir dir("failed-export");
  MakeSession(dir.Path("s"));
  {
    const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
    ExportRobomimic(session, dir.Path("out.hdf5"));
  }
  const auto size_before = fs::file_size(dir.Path("out.hdf5"));
  fs::resize_file(dir.Path("s/episodes/demo_2.h5"), 100);  // damaged after the first export
  const Session session = Session::Open(dir.Path("s"), Session::Access::kReadOnly);
  EXPECT_THAT(ErrorOf([&] { ExportRobomimic(session, dir.Path("out.hdf5")); }),
              HasSubstr("demo_2.h5"));
  EXPECT_EQ(fs::file_size(dir.Path("out.hdf5")), size_before);
  EXPECT_EQ(ImportRobomimic(dir.Path("out.hdf5"), dir.Path("copy")).demos, 2);
}

}  // namespace
}  // namespace recon::store
