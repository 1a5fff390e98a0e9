// kill -9 at exact points of every command that writes: the real `recon` binary, with
// tests/support/fault_shim.c preloaded, kills itself just before the first, middle and last flush
// of a file (its temporary written, not yet in place) and just after the first, middle and last
// rename (one file of a save of several in place, the next not yet), on a fresh copy of a
// session each time. A timed kill (CrashSafetyTest) lands where the clock puts it; these land on
// each step of a save. After every kill each file is the old one or whole and the session opens
// with nothing damaged; the command run again ends cleanly and leaves no temporary of the dead
// run (fault_walk.h, WalkKills).

#include <gtest/gtest.h>

#include "tests/app/fault_walk.h"

namespace recon {
namespace {

class KillAtWriteTest : public testing::FaultWalkTest {};

TEST_F(KillAtWriteTest, RecordingMoreDemonstrations) {
  WalkKills(Dynamic(), "record --session @S --demos 2 --play 2");
}

TEST_F(KillAtWriteTest, RecordingCameraEpisodes) {
  WalkKills(Tabletop(), "record --session @S --demos 2 --play 2");
}

TEST_F(KillAtWriteTest, Training) {
  WalkKills(Dynamic(), "train --session @S --methods baseline,recon --steps 50");
}

TEST_F(KillAtWriteTest, EvaluatingWithReplays) {
  WalkKills(Tabletop(), "eval --session @S --tests 1");
}

TEST_F(KillAtWriteTest, TheReport) { WalkKills(Dynamic(), "report @S"); }

TEST_F(KillAtWriteTest, Export) {
  WalkKills(Dynamic(), "session export @S --out @R/out.hdf5 --force");
}

TEST_F(KillAtWriteTest, Import) {
  WalkKills(Dynamic(), "session import @R/extra/export.hdf5 --session @R/imported");
}

TEST_F(KillAtWriteTest, MarkingAnEpisode) {
  WalkKills(Dynamic(), "session mark @S demo_1 --bad --note \"fell over\"");
}

TEST_F(KillAtWriteTest, DeletingAnEpisode) {
  WalkKills(Dynamic(), "session delete-episode @S demo_1");
}

TEST_F(KillAtWriteTest, DrawingAValidationSplit) {
  WalkKills(Dynamic(), "session split @S --valid 0.34 --seed 2");
}

TEST_F(KillAtWriteTest, RepairingALostManifest) {
  WalkKills(Dynamic(), "session repair @S --world dynamic2d --seed 3", "rm @S/session.json");
}

TEST_F(KillAtWriteTest, Calibration) {
  WalkKills(Dynamic(), "calibrate --sim --points 6 --out @R/calibration.json --force");
}

TEST_F(KillAtWriteTest, RenderingAnImage) {
  WalkKills(Dynamic(), "render --width 64 --height 48 --out @R/top.png --force");
}

TEST_F(KillAtWriteTest, AnExperimentsResults) {
  WalkKills(Dynamic(),
            "experiment static2d --demos 2 --runs 1 --steps 30 --baseline-steps 30 --tests 2 "
            "--jobs 1 --out @R/exp --force");
}

}  // namespace
}  // namespace recon
