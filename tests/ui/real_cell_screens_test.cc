// A real cell's screens, headless: the Calibrate step paced by the teacher, and the Rollouts
// step's trials on the real arm (set up, homing, running, judged, played back), each state a
// golden and each control the command it sends.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <variant>

#include "engine/core/error.h"
#include "tests/support/golden_image.h"
#include "tests/ui/studio_harness.h"
#include "tests/ui/studio_test_support.h"

namespace recon::ui {
namespace {

using testing::Progress;
using testing::SnapshotAt;

StudioSnapshot RealCell(Progress progress, teach::Step step) {
  StudioSnapshot s = SnapshotAt(progress, step);
  s.cell_kind = "real";
  s.studio_cell = "real";
  s.teacher_view = {};
  return s;
}

/// RECON's trials 1 (a success, with frames) and 2 (stopped, failed, no frames).
RealTrialsView TwoJudgedTrials() {
  RealTrialsView trials;
  trials.method = "recon";
  trials.label = "RECON (Play)";
  trials.successes = 1;
  trials.trials = {{1, true, false, "", true}, {2, false, true, "missed the toast", false}};
  return trials;
}

TEST(RealCellScreensTest, TheGuidedCalibrationSaysWhatToDoAndShowsWhatTheDevicesSee) {
  StudioHarness harness;
  StudioSnapshot s = RealCell(Progress::kBeaconAssigned, teach::Step::kCalibrate);
  harness.Show(s);
  EXPECT_TRUE(harness.driver().Drawn("Collect points and fit"));
  s.calibration.running = true;
  s.calibration.points_target = 8;
  s.calibration.points_collected = 3;
  GuidedCalibrationView& guided = s.calibration.guided.emplace();
  guided.points_target = 8;
  guided.points_taken = 3;
  guided.prompt = "Place 4 of 8: hold still...";
  guided.tag_seen = true;
  guided.tag_pixel = {100, 60};
  guided.taken_pixel = {{40, 30}, {120, 40}, {60, 90}};
  guided.beacon_uwb_m = {2.31f, -0.52f, 0.33f};
  guided.held_fraction = 0.6f;
  s.busy_with = "the calibration";
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("calibrate_guided")));
  EXPECT_TRUE(harness.driver().Drawn("camera##calibrate"));
  harness.Commands();
  harness.driver().Click("Cancel##calibration");
  EXPECT_TRUE(Last<CancelCalibration>(harness.Commands()).has_value());
}

TEST(RealCellScreensTest, ATrialIsSetUpRunStoppedAndJudgedFromTheRolloutsScreen) {
  StudioHarness harness;
  StudioSnapshot s = RealCell(Progress::kTrained, teach::Step::kRollouts);
  s.rollout_tests = 10;
  harness.Show(s);
  // No trial yet: one button per trained method.
  harness.Commands();
  harness.driver().Click("Run 10 trials of RECON (Play)");
  std::optional<StartTrials> start = Last<StartTrials>(harness.Commands());
  ASSERT_TRUE(start.has_value());
  EXPECT_EQ(start->method, "recon");
  EXPECT_EQ(start->trials, 10);

  s.busy_with = "the trials";
  s.trial.phase = TrialPhase::kSetUp;
  s.trial.method = "recon";
  s.trial.label = "RECON (Play)";
  s.trial.number = 3;
  s.trial.first = 3;
  s.trial.last = 12;
  s.trial.scene_seed = 1234;
  s.trial.layout = {{"bowl", {0.62f, -0.18f}, std::array<float, 2>{110, 80}},
                    {"plate", {0.55f, 0.35f}, std::array<float, 2>{40, 70}},
                    {"toast", {0.35f, 0.02f}, std::array<float, 2>{80, 40}}};
  s.trial.message =
      "Trial 3 stopped after 41 steps: the e-stop (e-stop pressed). The arm is stopped and the "
      "trial was not kept: set the layout up again and run it once the cause is fixed.";
  harness.Show(s);
  EXPECT_TRUE(
      ::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("trial_set_up")));
  harness.driver().Click("Ready: run trial 3");
  EXPECT_TRUE(Last<RunTrial>(harness.Commands()).has_value());
  harness.driver().Click("End trials");
  EXPECT_TRUE(Last<EndTrials>(harness.Commands()).has_value());
  // Under the e-stop the trial waits, and the button says why.
  s.safety.estop = true;
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Ready: run trial 3"), UserError);  // disabled
  EXPECT_FALSE(Last<RunTrial>(harness.Commands()).has_value());
  s.safety.estop = false;

  s.trial.message.clear();
  // Before the policy, the arm returns home: how far it has come, and the same STOP.
  s.trial.phase = TrialPhase::kHoming;
  s.trial.homing_progress = 0.4f;
  harness.Show(s);
  EXPECT_TRUE(
      ::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("trial_homing")));
  harness.driver().Click("STOP the trial");
  EXPECT_TRUE(Last<StopTrial>(harness.Commands()).has_value());

  s.trial.phase = TrialPhase::kRunning;
  s.trial.step = 57;
  s.trial.max_steps = 200;
  harness.Show(s);
  harness.driver().Click("STOP the trial");
  EXPECT_TRUE(Last<StopTrial>(harness.Commands()).has_value());

  s.trial.phase = TrialPhase::kJudge;
  s.trial.stopped = true;
  harness.Show(s);
  EXPECT_TRUE(
      ::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("trial_judge")));
  harness.driver().Click("Failure: took it to the bowl");
  std::optional<JudgeTrial> judged = Last<JudgeTrial>(harness.Commands());
  ASSERT_TRUE(judged.has_value());
  EXPECT_FALSE(judged->succeeded);
  EXPECT_EQ(judged->reason, "took it to the bowl");
  harness.driver().Click("Success");
  judged = Last<JudgeTrial>(harness.Commands());
  ASSERT_TRUE(judged.has_value());
  EXPECT_TRUE(judged->succeeded);

  // Judged trials are listed, and one with frames plays back.
  s.trial = {};
  s.busy_with.clear();
  s.real_trials = {TwoJudgedTrials()};
  s.trial_playback.method = "recon";
  s.trial_playback.number = 1;
  s.trial_playback.frame = 4;
  s.trial_playback.frames = 20;
  s.trial_playback.image = testing::SyntheticCamera();
  s.trial_playback.image_frame = 1;
  harness.Show(s);
  harness.driver().Click("Play##recon1");
  std::optional<ShowTrialFrame> shown = Last<ShowTrialFrame>(harness.Commands());
  ASSERT_TRUE(shown.has_value());
  EXPECT_EQ(shown->number, 1);
  EXPECT_EQ(shown->frame, 0);
  EXPECT_THROW(harness.driver().Click("Play##recon2"), UserError);  // no frames kept: disabled
}

TEST(RealCellScreensTest, ASimulatedSessionOnARealCellShowsItsSimulatedRolloutsBesideTheTrials) {
  StudioHarness harness;
  StudioSnapshot s = RealCell(Progress::kDone, teach::Step::kRollouts);
  s.cell_kind = "simulated";  // taught in the simulated cell, here for trials on the arm
  teach::WorkflowFacts facts = testing::FactsAt(Progress::kDone);
  facts.taught_elsewhere = "Taught in the simulated cell, recorded there";
  s.steps = teach::EvaluateWorkflow(facts);
  for (int i = 0; i < teach::kNumSteps; ++i) {
    s.can_open[i] = teach::CanOpen(facts, teach::kAllSteps[i]);
  }
  s.rollout_tests = 10;
  s.real_trials = {TwoJudgedTrials()};
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("rollouts_sim_to_real")));
  // Both: trials on the arm, and the simulated rollouts, which can be run again here.
  harness.Commands();
  harness.driver().Click("Run 10 trials of RECON (Play)");
  EXPECT_TRUE(Last<StartTrials>(harness.Commands()).has_value());
  harness.driver().Click("Run rollouts");
  EXPECT_TRUE(Last<RunRollouts>(harness.Commands()).has_value());

  // A real cell's own session has no simulated rollouts to show or run.
  s.cell_kind = "real";
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Run rollouts"), UserError);
  harness.driver().Click("Run 10 trials of RECON (Play)");
  EXPECT_TRUE(Last<StartTrials>(harness.Commands()).has_value());
}

}  // namespace
}  // namespace recon::ui
