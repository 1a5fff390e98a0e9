// A failing fsync or rename, for every command that writes (DiskFullTest covers the write itself).
// The real `recon` binary runs with tests/support/fault_shim.c preloaded: a first run counts the
// process's flushes of files, flushes of folders and renames, then each call in turn (or some
// spread over the run, CallsToFail) fails with EIO, as on a failing disk or a network file
// system, on a fresh copy of the session. After every run:
//   - a failed flush of a folder is not an error (it follows a rename that has happened): the
//     command succeeds;
//   - with a file's flush or a rename failing, the command succeeded, or it exited 2 saying
//     "Input/output error" about a file the user knows (never our temporary's or staging
//     folder's name), and never crashed; and such a failure is never ignored: some run fails;
//   - no temporary or staging folder is left;
//   - every file is either as it was or complete (HDF5 files pass their checksums, checkpoints
//     load, JSON parses, images, drawings, tables and pages end where they should);
//   - the session still opens and no episode reads as damaged.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/app/fault_walk.h"

namespace recon {
namespace {

using testing::CommandResult;
using ::testing::HasSubstr;
using testing::RunCommand;

class FaultInjectionTest : public testing::FaultWalkTest {};

// The shim itself: a mistyped setting would inject nothing and let the walks above pass for the
// wrong reason, so it stops the program instead.
TEST_F(FaultInjectionTest, AMistypedFaultSettingStopsTheProgram) {
  for (const std::string setting : {"fsnyc:1", "fsync", "rename:0", "rename:2x", "dirsync:-1"}) {
    const CommandResult r = RunCommand(
        "RECON_FAULT=" + setting + " LD_PRELOAD=" + RECON_FAULT_SHIM + " " + RECON_CLI + " --help");
    EXPECT_EQ(r.exit_code, 97) << setting << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("is not fsync:N, dirsync:N or rename:N")) << setting;
  }
  const CommandResult action = RunCommand(
      "RECON_FAULT=fsync:1 RECON_FAULT_ACTION=explode LD_PRELOAD=" + std::string(RECON_FAULT_SHIM) +
      " " + RECON_CLI + " --help");
  EXPECT_EQ(action.exit_code, 97) << action.output;
  EXPECT_THAT(action.output, HasSubstr("is not fail, kill-before or kill-after"));
  const CommandResult valid = RunCommand(std::string("RECON_FAULT=fsync:1 LD_PRELOAD=") +
                                         RECON_FAULT_SHIM + " " + RECON_CLI + " --help");
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
}

TEST_F(FaultInjectionTest, RecordingMoreDemonstrations) {
  WalkFaults(Dynamic(), "record --session @S --demos 2 --play 2");
}

TEST_F(FaultInjectionTest, RecordingCameraEpisodes) {
  WalkFaults(Tabletop(), "record --session @S --demos 2 --play 2");
}

TEST_F(FaultInjectionTest, Training) {
  WalkFaults(Dynamic(), "train --session @S --methods baseline,recon --steps 50");
}

TEST_F(FaultInjectionTest, EvaluatingWithReplays) {
  WalkFaults(Tabletop(), "eval --session @S --tests 1");
}

TEST_F(FaultInjectionTest, TheReport) { WalkFaults(Dynamic(), "report @S"); }

TEST_F(FaultInjectionTest, Export) { WalkFaults(Dynamic(), "session export @S --out @R/out.hdf5"); }

TEST_F(FaultInjectionTest, Import) {
  WalkFaults(Dynamic(), "session import @R/extra/export.hdf5 --session @R/imported");
}

TEST_F(FaultInjectionTest, MarkingAnEpisode) {
  WalkFaults(Dynamic(), "session mark @S demo_1 --bad --note \"fell over\"");
}

TEST_F(FaultInjectionTest, DeletingAnEpisode) {
  WalkFaults(Dynamic(), "session delete-episode @S demo_1");
}

TEST_F(FaultInjectionTest, DrawingAValidationSplit) {
  WalkFaults(Dynamic(), "session split @S --valid 0.34 --seed 2");
}

TEST_F(FaultInjectionTest, RepairingALostManifest) {
  WalkFaults(Dynamic(), "session repair @S --world dynamic2d --seed 3", "rm @S/session.json");
}

TEST_F(FaultInjectionTest, Calibration) {
  WalkFaults(Dynamic(), "calibrate --sim --points 6 --out @R/calibration.json");
}

TEST_F(FaultInjectionTest, RenderingAnImage) {
  WalkFaults(Dynamic(), "render --width 64 --height 48 --out @R/top.png");
}

TEST_F(FaultInjectionTest, AnExperimentsResults) {
  WalkFaults(Dynamic(),
             "experiment static2d --demos 2 --runs 1 --steps 30 --baseline-steps 30 --tests 2 "
             "--jobs 1 --out @R/exp");
}

}  // namespace
}  // namespace recon
