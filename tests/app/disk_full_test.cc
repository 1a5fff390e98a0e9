// A full disk, for every command that writes. Each command runs on a small file system of its own
// (a tmpfs mounted in a private mount namespace, so nothing outside the test sees it) holding a
// copy of a session and a filler file that leaves a given number of bytes free. The free sizes
// walk from nothing to just short of what the command writes (measured by a first run with room
// to spare), so the disk fills at a different write each time: the first episode, the manifest,
// the index, a checkpoint, a training record, a replay, a figure, an export. After every run:
//   - the command succeeded, or it exited 2 saying "No space left on device" about a file the
//     user knows (never our temporary's name), and never crashed;
//   - no temporary is left behind;
//   - every file is either as it was or complete (HDF5 files pass their checksums, checkpoints
//     load, JSON parses, images and pages end where they should);
//   - the session still opens and no episode reads as damaged.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tests/app/run_recon.h"
#include "tests/app/saved_files.h"
#include "tests/app/small_disk.h"
#include "tests/app/walk_checks.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::FullDiskRun;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadBytes;
using testing::SmallDisk;
using testing::Snapshot;

/// Each test gets a folder of its own and two sessions: a Dynamic 2D one (3 demonstrations,
/// play data, both methods trained and evaluated) and a tabletop one with camera images.
class DiskFullTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::path("/tmp") / ("disk_full_test_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "extra");
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    work_ = root_ / test;
    fs::create_directories(work_);
  }

  /// Runs `args` once with room to spare (it must succeed), then with the disk filling at points
  /// spread over what that run wrote, checking the invariants above after each.
  void WalkFreeSpace(const fs::path& session, const std::string& args,
                     const std::string& prepare = "") {
    SmallDisk disk(session, root_ / "extra", work_);
    const std::map<std::string, std::string> before = Snapshot(session);
    const FullDiskRun roomy = disk.Run(args, SmallDisk::kPlentyBytes / 2, prepare, "roomy_");
    ASSERT_EQ(roomy.result.exit_code, 0) << args << "\n" << roomy.result.output;
    // What the command writes: every file new or changed in the session, and beside it.
    uint64_t written = 0;
    for (const auto& [name, bytes] : Snapshot(roomy.root)) {
      const std::string in_session = name.rfind("s/", 0) == 0 ? name.substr(2) : "";
      const auto old = before.find(in_session);
      if (name.rfind("extra/", 0) == 0) continue;
      if (old == before.end() || old->second != bytes) written += bytes.size();
    }
    ASSERT_GT(written, 0u) << args << " wrote nothing";
    const std::set<uint64_t> free_sizes = testing::FreeSizesToWalk(written);
    int failures = 0;
    for (const uint64_t free_bytes : free_sizes) {
      SCOPED_TRACE(args + " with " + std::to_string(free_bytes) + " bytes free (" +
                   std::to_string(written) + " written with room to spare)");
      const FullDiskRun run = disk.Run(args, free_bytes, prepare);
      const CommandResult& r = run.result;
      ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.output;
      if (r.exit_code == 2) {
        ++failures;
        EXPECT_THAT(r.output, HasSubstr("No space left on device"));
        EXPECT_THAT(r.output, Not(HasSubstr(".tmp.")));
      }
      testing::ExpectEveryFileOldOrWhole(run.root, before, root_ / "extra",
                                         /*temporaries_allowed=*/false);
      if (fs::exists(run.root / "s" / "session.json"))
        testing::ExpectNoEpisodeDamaged(run.root / "s");
    }
    // The walk must have reached the disk: with nothing free, every command here fails.
    EXPECT_GT(failures, 0) << args << " never ran out of space";
  }

  static fs::path Dynamic() { return testing::DynamicWalkSession(root_); }
  static fs::path Tabletop() { return testing::TabletopWalkSession(root_); }

  static fs::path root_;
  fs::path work_;
};

fs::path DiskFullTest::root_;

TEST_F(DiskFullTest, RecordingMoreDemonstrations) {
  WalkFreeSpace(Dynamic(), "record --session @S --demos 2 --play 2");
}

TEST_F(DiskFullTest, RecordingCameraEpisodes) {
  WalkFreeSpace(Tabletop(), "record --session @S --demos 2 --play 2");
}

TEST_F(DiskFullTest, Training) {
  WalkFreeSpace(Dynamic(), "train --session @S --methods baseline,recon --steps 50");
}

TEST_F(DiskFullTest, EvaluatingWithReplays) {
  WalkFreeSpace(Tabletop(), "eval --session @S --tests 1");
}

TEST_F(DiskFullTest, TheReport) { WalkFreeSpace(Dynamic(), "report @S"); }

TEST_F(DiskFullTest, Export) { WalkFreeSpace(Dynamic(), "session export @S --out @R/out.hdf5"); }

TEST_F(DiskFullTest, Import) {
  WalkFreeSpace(Dynamic(), "session import @R/extra/export.hdf5 --session @R/imported");
}

TEST_F(DiskFullTest, MarkingAnEpisode) {
  WalkFreeSpace(Dynamic(), "session mark @S demo_1 --bad --note \"fell over\"");
}

TEST_F(DiskFullTest, RepairingALostManifest) {
  WalkFreeSpace(Dynamic(), "session repair @S --world dynamic2d --seed 3", "rm @S/session.json");
}

TEST_F(DiskFullTest, AnExperimentsResults) {
  WalkFreeSpace(Dynamic(),
                "experiment static2d --demos 2 --runs 1 --steps 30 --baseline-steps 30 --tests 2 "
                "--jobs 1 --out @R/exp");
}

TEST_F(DiskFullTest, Calibration) {
  WalkFreeSpace(Dynamic(), "calibrate --sim --points 6 --out @R/calibration.json");
}

}  // namespace
}  // namespace recon
