#include "engine/teach/workflow.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

namespace recon::teach {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

StepStatus StatusOf(const WorkflowFacts& facts, Step step) {
  return EvaluateWorkflow(facts).at(static_cast<int>(step));
}

StepState StateOf(const WorkflowFacts& facts, Step step) { return StatusOf(facts, step).state; }

std::string Meters(double m) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f m", m);
  return text;
}

/// "(Cell)": how a reason names the step to go to.
std::string StepTag(Step step) { return std::string("(") + StepTitle(step) + ")"; }

/// A tabletop-like session up to a passed calibration: one beacon, on the plate.
WorkflowFacts CalibratedFacts() {
  WorkflowFacts facts;
  facts.session_open = true;
  facts.cell_connected = true;
  facts.beacons_required = 1;
  facts.beacons_assigned = 1;
  facts.calibration_present = true;
  facts.calibration_passed = true;
  facts.calibration_rmse_m = 0.031;
  return facts;
}

/// CalibratedFacts with enough demonstrations to train.
WorkflowFacts RecordedFacts() {
  WorkflowFacts facts = CalibratedFacts();
  facts.min_demos = 3;
  facts.demos = 3;
  facts.demo_seconds = 412;
  return facts;
}

TEST(WorkflowTest, StepsHaveTheStudioTitlesAndAPurpose) {
  const std::vector<std::string> expected = {"Cell",      "Beacons", "Calibrate", "Record",
                                             "Play data", "Train",   "Rollouts",  "Report"};
  ASSERT_EQ(static_cast<int>(kAllSteps.size()), kNumSteps);
  for (int i = 0; i < kNumSteps; ++i) {
    EXPECT_EQ(static_cast<int>(kAllSteps[i]), i);
    EXPECT_EQ(StepTitle(kAllSteps[i]), expected[i]);
    const std::string purpose = StepPurpose(kAllSteps[i]);
    EXPECT_GT(purpose.size(), 20u) << expected[i];
    EXPECT_THAT(purpose, EndsWith(".")) << expected[i];
  }
  const std::vector<StepStatus> steps = EvaluateWorkflow({});
  ASSERT_EQ(static_cast<int>(steps.size()), kNumSteps);
  for (int i = 0; i < kNumSteps; ++i) EXPECT_EQ(steps[i].step, kAllSteps[i]);
}

TEST(WorkflowTest, FreshStudioStartsAtCellAndBlocksEverythingElse) {
  const WorkflowFacts fresh;
  EXPECT_EQ(NextStep(fresh), Step::kCell);
  EXPECT_EQ(StateOf(fresh, Step::kCell), StepState::kReady);
  EXPECT_THAT(StatusOf(fresh, Step::kCell).summary, HasSubstr("No session open"));
  EXPECT_TRUE(CanOpen(fresh, Step::kCell));
  for (Step step : kAllSteps) {
    if (step == Step::kCell) continue;
    const StepStatus status = StatusOf(fresh, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    // Every reason sends the teacher to the one step they can act on.
    EXPECT_THAT(status.why_blocked, HasSubstr("session")) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kCell))) << StepTitle(step);
    EXPECT_FALSE(CanOpen(fresh, step)) << StepTitle(step);
  }
}

TEST(WorkflowTest, MissingDevicesAreNamedInCellAndInTheReasons) {
  WorkflowFacts facts;
  facts.session_open = true;
  facts.missing_devices = {"camera", "beacons"};
  EXPECT_EQ(NextStep(facts), Step::kCell);
  EXPECT_EQ(StateOf(facts, Step::kCell), StepState::kReady);
  const std::string names = facts.missing_devices[0] + ", " + facts.missing_devices[1];
  EXPECT_THAT(StatusOf(facts, Step::kCell).summary, HasSubstr(names));
  EXPECT_THAT(StatusOf(facts, Step::kBeacons).why_blocked, HasSubstr("Connect " + names));
  EXPECT_THAT(StatusOf(facts, Step::kBeacons).why_blocked, EndsWith(StepTag(Step::kCell)));
}

// Walks a whole session fact by fact: each change moves the teacher on exactly as the studio's
// step list promises, and a step once done stays done.
TEST(WorkflowTest, FullSessionAdvancesStepByStep) {
  std::vector<Step> next_steps;
  std::set<Step> done;
  auto check = [&](const WorkflowFacts& facts, Step expected_next, const std::string& stage) {
    SCOPED_TRACE(stage);
    const Step next = NextStep(facts);
    EXPECT_EQ(next, expected_next) << StepTitle(next);
    if (next_steps.empty() || next_steps.back() != next) next_steps.push_back(next);
    EXPECT_NE(StateOf(facts, next), StepState::kBlocked);
    for (Step step : kAllSteps) {
      const StepStatus status = StatusOf(facts, step);
      if (static_cast<int>(step) <= static_cast<int>(next)) {
        EXPECT_TRUE(CanOpen(facts, step)) << "going back to " << StepTitle(step);
      }
      if (status.state == StepState::kBlocked) {
        EXPECT_FALSE(CanOpen(facts, step)) << StepTitle(step);
        EXPECT_THAT(status.why_blocked, Not(IsEmpty())) << StepTitle(step);
      } else {
        EXPECT_THAT(status.why_blocked, IsEmpty()) << StepTitle(step);
      }
      if (done.count(step) > 0) {
        EXPECT_EQ(status.state, StepState::kDone) << StepTitle(step);
      }
      if (status.state == StepState::kDone) done.insert(step);
    }
  };

  WorkflowFacts facts;
  check(facts, Step::kCell, "fresh");
  facts.session_open = true;
  facts.missing_devices = {"beacons"};
  check(facts, Step::kCell, "session open, beacons missing");
  facts.cell_connected = true;
  facts.missing_devices.clear();
  facts.beacons_required = 1;
  facts.unmarked_objects = {"the plate"};
  check(facts, Step::kBeacons, "cell connected");
  EXPECT_THAT(StatusOf(facts, Step::kCalibrate).why_blocked,
              HasSubstr("Assign a beacon to " + facts.unmarked_objects[0]));
  EXPECT_THAT(StatusOf(facts, Step::kCalibrate).why_blocked, EndsWith(StepTag(Step::kBeacons)));
  facts.beacons_assigned = 1;
  facts.unmarked_objects.clear();
  check(facts, Step::kCalibrate, "beacon assigned");
  EXPECT_THAT(StatusOf(facts, Step::kRecord).why_blocked, EndsWith(StepTag(Step::kCalibrate)));
  facts.calibration_present = true;
  facts.calibration_passed = true;
  facts.calibration_rmse_m = 0.031;
  check(facts, Step::kRecord, "calibrated");
  EXPECT_THAT(StatusOf(facts, Step::kCalibrate).summary,
              HasSubstr(Meters(facts.calibration_rmse_m)));
  EXPECT_THAT(StatusOf(facts, Step::kTrain).why_blocked, EndsWith(StepTag(Step::kRecord)));
  EXPECT_EQ(StateOf(facts, Step::kPlay), StepState::kReady);
  facts.min_demos = 3;
  facts.demos = 2;
  check(facts, Step::kRecord, "two of three demonstrations");
  EXPECT_EQ(StateOf(facts, Step::kReport), StepState::kReady);
  facts.demos = 3;
  facts.demo_seconds = 412;
  // Play data is optional: it is ready, but the teacher is sent on to Train.
  check(facts, Step::kTrain, "enough demonstrations");
  EXPECT_EQ(StateOf(facts, Step::kPlay), StepState::kReady);
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kBlocked);
  EXPECT_THAT(StatusOf(facts, Step::kRollouts).why_blocked, EndsWith(StepTag(Step::kTrain)));
  facts.trained_methods = {kBaselineMethod};
  check(facts, Step::kTrain, "Baseline trained");
  EXPECT_EQ(StateOf(facts, Step::kTrain), StepState::kReady);
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kReady);
  facts.trained_methods.push_back(kReconMethod);
  check(facts, Step::kRollouts, "both trained");
  facts.evaluated_methods = {kBaselineMethod};
  check(facts, Step::kRollouts, "Baseline evaluated");
  // RECON retrained after its rollouts: they are of an older model, so RECON is not evaluated.
  facts.outdated_evaluations = {kReconMethod};
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kReady);
  EXPECT_THAT(StatusOf(facts, Step::kRollouts).summary,
              HasSubstr("1 of 2 trained methods evaluated; out of date: RECON"));
  facts.outdated_evaluations.clear();
  facts.evaluated_methods.push_back(kReconMethod);
  check(facts, Step::kReport, "both evaluated");
  facts.report_written = true;
  check(facts, Step::kReport, "report written");
  facts.play_samples = 600;
  check(facts, Step::kReport, "play data recorded");

  const std::vector<Step> expected = {Step::kCell,   Step::kBeacons, Step::kCalibrate,
                                      Step::kRecord, Step::kTrain,   Step::kRollouts,
                                      Step::kReport};
  EXPECT_EQ(next_steps, expected);
  for (Step step : kAllSteps) {
    EXPECT_EQ(StateOf(facts, step), StepState::kDone) << StepTitle(step);
  }
}

TEST(WorkflowTest, FailedCalibrationKeepsRecordBlockedAndCalibrateReady) {
  WorkflowFacts facts = CalibratedFacts();
  facts.calibration_passed = false;
  facts.calibration_rmse_m = 0.143;
  const std::string rmse = Meters(facts.calibration_rmse_m);
  EXPECT_EQ(NextStep(facts), Step::kCalibrate);
  const StepStatus calibrate = StatusOf(facts, Step::kCalibrate);
  EXPECT_EQ(calibrate.state, StepState::kReady);
  EXPECT_THAT(calibrate.summary, HasSubstr("Failed"));
  EXPECT_THAT(calibrate.summary, HasSubstr(rmse));
  for (Step step : {Step::kRecord, Step::kPlay}) {
    const StepStatus status = StatusOf(facts, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, HasSubstr(rmse)) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kCalibrate))) << StepTitle(step);
    EXPECT_FALSE(CanOpen(facts, step)) << StepTitle(step);
  }
  EXPECT_TRUE(CanOpen(facts, Step::kCalibrate));

  // A missing calibration reads differently from a failed one.
  facts.calibration_present = false;
  EXPECT_THAT(StatusOf(facts, Step::kCalibrate).summary, HasSubstr("Not calibrated"));
  EXPECT_THAT(StatusOf(facts, Step::kRecord).why_blocked, Not(HasSubstr(rmse)));
  // "Passed" without a calibration present is not a calibration.
  facts.calibration_passed = true;
  EXPECT_EQ(StateOf(facts, Step::kCalibrate), StepState::kReady);
  EXPECT_EQ(StateOf(facts, Step::kRecord), StepState::kBlocked);
}

TEST(WorkflowTest, CanOpenGoesBackButNotAhead) {
  WorkflowFacts facts = CalibratedFacts();
  facts.calibration_present = false;
  ASSERT_EQ(NextStep(facts), Step::kCalibrate);
  for (Step step : {Step::kCell, Step::kBeacons, Step::kCalibrate}) {
    EXPECT_TRUE(CanOpen(facts, step)) << StepTitle(step);
  }
  for (Step step : {Step::kRecord, Step::kPlay, Step::kTrain, Step::kRollouts, Step::kReport}) {
    EXPECT_FALSE(CanOpen(facts, step)) << StepTitle(step);
  }

  // Later, every earlier step is still open: a teacher can re-assign beacons or re-calibrate.
  facts = RecordedFacts();
  facts.trained_methods = {kBaselineMethod, kReconMethod};
  ASSERT_EQ(NextStep(facts), Step::kRollouts);
  for (Step step : kAllSteps) EXPECT_TRUE(CanOpen(facts, step)) << StepTitle(step);
}

TEST(WorkflowTest, RecordingDemosIsBusyAndBlocksWhatWouldChangeTheData) {
  WorkflowFacts facts = RecordedFacts();
  facts.trained_methods = {kBaselineMethod};
  facts.recording_demos = true;
  EXPECT_EQ(NextStep(facts), Step::kRecord);
  const StepStatus record = StatusOf(facts, Step::kRecord);
  EXPECT_EQ(record.state, StepState::kBusy);
  EXPECT_THAT(record.why_blocked, IsEmpty());
  for (Step step : {Step::kBeacons, Step::kCalibrate, Step::kPlay, Step::kTrain}) {
    const StepStatus status = StatusOf(facts, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, HasSubstr("Wait for")) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kRecord))) << StepTitle(step);
  }
  // Steps the recording does not touch go on.
  EXPECT_EQ(StateOf(facts, Step::kCell), StepState::kDone);
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kReady);
  EXPECT_EQ(StateOf(facts, Step::kReport), StepState::kReady);
  // Going back stays possible (to look), and Train, blocked only by the recording, can be opened.
  for (Step step : kAllSteps) EXPECT_TRUE(CanOpen(facts, step)) << StepTitle(step);

  facts.recording_demos = false;
  EXPECT_EQ(StateOf(facts, Step::kTrain), StepState::kReady);
  EXPECT_EQ(StateOf(facts, Step::kBeacons), StepState::kDone);
}

TEST(WorkflowTest, RecordingPlayIsBusyAndBlocksRecordAndTrain) {
  WorkflowFacts facts = RecordedFacts();
  facts.recording_play = true;
  EXPECT_EQ(NextStep(facts), Step::kPlay);
  EXPECT_EQ(StateOf(facts, Step::kPlay), StepState::kBusy);
  for (Step step : {Step::kRecord, Step::kTrain}) {
    const StepStatus status = StatusOf(facts, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kPlay))) << StepTitle(step);
  }
}

TEST(WorkflowTest, TrainingIsBusyAndBlocksRecordAndPlay) {
  WorkflowFacts facts = RecordedFacts();
  facts.training = true;
  EXPECT_EQ(NextStep(facts), Step::kTrain);
  const StepStatus train = StatusOf(facts, Step::kTrain);
  EXPECT_EQ(train.state, StepState::kBusy);
  EXPECT_THAT(train.why_blocked, IsEmpty());
  for (Step step : {Step::kRecord, Step::kPlay}) {
    const StepStatus status = StatusOf(facts, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, HasSubstr("Wait for training to finish or cancel it"));
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kTrain)));
    EXPECT_TRUE(CanOpen(facts, step)) << "going back to " << StepTitle(step);
  }
  // Nothing trained yet: Rollouts waits for training.
  const StepStatus rollouts = StatusOf(facts, Step::kRollouts);
  EXPECT_EQ(rollouts.state, StepState::kBlocked);
  EXPECT_THAT(rollouts.why_blocked, HasSubstr("Wait for training"));
  EXPECT_FALSE(CanOpen(facts, Step::kRollouts));
  // Calibration and beacons do not change data already recorded: they stay done.
  EXPECT_EQ(StateOf(facts, Step::kCalibrate), StepState::kDone);
  EXPECT_EQ(StateOf(facts, Step::kBeacons), StepState::kDone);

  // RECON trains after the Baseline: the Baseline's rollouts can run meanwhile.
  facts.trained_methods = {kBaselineMethod};
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kReady);
  EXPECT_TRUE(CanOpen(facts, Step::kRollouts));
}

// A step missing a prerequisite says so even while an activity runs: waiting would not help.
TEST(WorkflowTest, MissingPrerequisiteOutlastsARunningActivity) {
  WorkflowFacts facts = RecordedFacts();
  facts.training = true;
  facts.calibration_passed = false;  // a re-calibration failed while the data trains
  for (Step step : {Step::kRecord, Step::kPlay}) {
    const StepStatus status = StatusOf(facts, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kCalibrate))) << StepTitle(step);
  }
  EXPECT_EQ(StateOf(facts, Step::kCalibrate), StepState::kReady);
  EXPECT_EQ(NextStep(facts), Step::kTrain);
  EXPECT_TRUE(CanOpen(facts, Step::kRecord));  // going back, to look
}

TEST(WorkflowTest, ReportNeedsAnOpenSessionWithADemonstration) {
  WorkflowFacts facts = RecordedFacts();
  facts.session_open = false;
  EXPECT_EQ(StateOf(facts, Step::kReport), StepState::kBlocked);
  EXPECT_THAT(StatusOf(facts, Step::kReport).why_blocked, EndsWith(StepTag(Step::kCell)));
  facts.session_open = true;
  facts.demos = 0;
  EXPECT_EQ(StateOf(facts, Step::kReport), StepState::kBlocked);
  EXPECT_THAT(StatusOf(facts, Step::kReport).why_blocked, EndsWith(StepTag(Step::kRecord)));
  facts.demos = 1;  // fewer than min_demos is enough for a report
  EXPECT_EQ(StateOf(facts, Step::kReport), StepState::kReady);
  facts.report_written = true;
  EXPECT_EQ(StateOf(facts, Step::kReport), StepState::kDone);
  EXPECT_THAT(StatusOf(facts, Step::kReport).summary, HasSubstr("written"));
}

TEST(WorkflowTest, TaskWithoutBeaconsSkipsBeaconsAndTrainsTheBaselineOnly) {
  WorkflowFacts facts;
  facts.session_open = true;
  facts.cell_connected = true;
  facts.beacons_required = 0;
  for (Step step : {Step::kBeacons, Step::kCalibrate, Step::kPlay}) {
    EXPECT_EQ(StateOf(facts, step), StepState::kDone) << StepTitle(step);
  }
  EXPECT_THAT(StatusOf(facts, Step::kBeacons).summary, HasSubstr("No beacons in this task"));
  EXPECT_THAT(StatusOf(facts, Step::kBeacons).summary, HasSubstr("Baseline only"));
  EXPECT_EQ(NextStep(facts), Step::kRecord);

  facts.demos = 1;
  facts.demo_seconds = 30;
  EXPECT_EQ(NextStep(facts), Step::kTrain);
  facts.trained_methods = {kBaselineMethod};
  EXPECT_EQ(StateOf(facts, Step::kTrain), StepState::kDone);
  EXPECT_THAT(StatusOf(facts, Step::kTrain).summary, HasSubstr("no RECON"));
  EXPECT_EQ(NextStep(facts), Step::kRollouts);
  facts.evaluated_methods = {kBaselineMethod};
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kDone);
  EXPECT_EQ(NextStep(facts), Step::kReport);

  // With a beacon, the Baseline alone is not enough.
  facts.beacons_required = 1;
  facts.beacons_assigned = 1;
  facts.calibration_present = true;
  facts.calibration_passed = true;
  EXPECT_EQ(StateOf(facts, Step::kTrain), StepState::kReady);
  EXPECT_EQ(NextStep(facts), Step::kTrain);
}

TEST(WorkflowTest, SummariesReportTheirCounts) {
  WorkflowFacts facts = CalibratedFacts();
  facts.beacons_required = 2;
  facts.beacons_assigned = 1;
  EXPECT_THAT(StatusOf(facts, Step::kBeacons).summary,
              HasSubstr(std::to_string(facts.beacons_assigned) + " of " +
                        std::to_string(facts.beacons_required) + " beacons assigned"));
  EXPECT_THAT(
      StatusOf(facts, Step::kCalibrate).why_blocked,
      HasSubstr(std::to_string(facts.beacons_required - facts.beacons_assigned) + " more beacon"));
  facts.beacons_required = 1;
  EXPECT_THAT(StatusOf(facts, Step::kBeacons).summary, HasSubstr("1 of 1 beacon assigned"));

  facts.min_demos = 5;
  facts.demos = 2;
  EXPECT_THAT(StatusOf(facts, Step::kRecord).summary,
              HasSubstr(std::to_string(facts.demos) + " of " + std::to_string(facts.min_demos) +
                        " demonstrations"));
  EXPECT_THAT(StatusOf(facts, Step::kTrain).why_blocked,
              HasSubstr("Record " + std::to_string(facts.min_demos - facts.demos) +
                        " more demonstrations"));
  facts.demos = 5;
  facts.demo_seconds = 556;
  EXPECT_THAT(StatusOf(facts, Step::kRecord).summary,
              HasSubstr(std::to_string(facts.demos) + " demonstrations, " +
                        std::to_string(static_cast<int>(facts.demo_seconds)) + " s"));

  facts.play_samples = 1200;
  const StepStatus play = StatusOf(facts, Step::kPlay);
  EXPECT_THAT(play.summary, HasSubstr(std::to_string(facts.play_samples) + " play samples"));
  EXPECT_THAT(play.summary, HasSubstr("optional"));
  EXPECT_THAT(play.summary, HasSubstr("RECON"));
  facts.play_samples = 0;
  EXPECT_THAT(StatusOf(facts, Step::kPlay).summary, HasSubstr("optional"));

  facts.trained_methods = {kBaselineMethod, kReconMethod};
  facts.evaluated_methods = {kReconMethod};
  const StepStatus rollouts = StatusOf(facts, Step::kRollouts);
  EXPECT_THAT(rollouts.summary,
              HasSubstr(std::to_string(facts.evaluated_methods.size()) + " of " +
                        std::to_string(facts.trained_methods.size()) + " trained methods"));
  EXPECT_THAT(rollouts.summary, HasSubstr("not yet: Baseline"));
  EXPECT_THAT(StatusOf(facts, Step::kReport).summary,
              HasSubstr(std::to_string(facts.demos) + " demonstrations"));
}

// Over every combination of the facts' switches: the next step is never blocked, every step up
// to it can be opened, and a blocked step (only a blocked one) says which step to go to.
TEST(WorkflowTest, ASessionTaughtInAnotherCellTrainsAndRollsOutButRecordsNothingHere) {
  const std::string why = "Taught in the simulated cell, recorded there";
  WorkflowFacts facts = RecordedFacts();
  facts.play_samples = 40;
  facts.taught_elsewhere = why;
  const Step cell_steps[] = {Step::kBeacons, Step::kCalibrate, Step::kRecord, Step::kPlay};
  for (Step step : cell_steps) {
    const StepStatus status = StatusOf(facts, step);
    EXPECT_EQ(status.state, StepState::kBlocked) << StepTitle(step);
    EXPECT_THAT(status.why_blocked, HasSubstr(why));
    EXPECT_THAT(status.why_blocked, EndsWith(StepTag(Step::kTrain)));
    // What the session holds is still said.
    EXPECT_THAT(StatusOf(facts, Step::kRecord).summary, HasSubstr("3 demonstrations"));
  }
  EXPECT_EQ(StateOf(facts, Step::kTrain), StepState::kReady);
  EXPECT_EQ(NextStep(facts), Step::kTrain);
  // The teacher can still look at what was recorded (the steps before the next one open).
  EXPECT_TRUE(CanOpen(facts, Step::kRecord));

  facts.trained_methods = {kBaselineMethod, kReconMethod};
  EXPECT_THAT(StatusOf(facts, Step::kRecord).why_blocked, EndsWith(StepTag(Step::kRollouts)));
  EXPECT_EQ(StateOf(facts, Step::kRollouts), StepState::kReady);
  EXPECT_EQ(NextStep(facts), Step::kRollouts);

  // Too few demonstrations to train: Train says so without sending the teacher to Record.
  facts = CalibratedFacts();
  facts.min_demos = 3;
  facts.demos = 1;
  facts.taught_elsewhere = why;
  EXPECT_THAT(StatusOf(facts, Step::kRecord).why_blocked, EndsWith(StepTag(Step::kCell)));
  EXPECT_THAT(StatusOf(facts, Step::kTrain).why_blocked, HasSubstr(why));
  EXPECT_EQ(NextStep(facts), Step::kReport);
  facts.demos = 0;  // not even a report: another session
  EXPECT_EQ(NextStep(facts), Step::kCell);

  // Taught here, the same facts leave every step to its own rule.
  facts.taught_elsewhere.clear();
  EXPECT_EQ(StateOf(facts, Step::kRecord), StepState::kReady);
}

TEST(WorkflowTest, InvariantsHoldForEveryCombinationOfFacts) {
  constexpr int kSwitches = 15;
  int blocked_seen = 0;
  for (int bits = 0; bits < (1 << kSwitches); ++bits) {
    auto on = [bits](int i) { return ((bits >> i) & 1) != 0; };
    WorkflowFacts facts;
    facts.session_open = on(0);
    facts.cell_connected = on(1);
    facts.beacons_required = on(2) ? 1 : 0;
    facts.beacons_assigned = on(3) ? 1 : 0;
    facts.calibration_present = on(4);
    facts.calibration_passed = on(5);
    facts.demos = on(6) ? 2 : 0;
    facts.play_samples = on(7) ? 100 : 0;
    facts.recording_demos = on(8);
    facts.training = on(9);
    if (on(10)) facts.trained_methods.push_back(kBaselineMethod);
    if (on(11)) facts.trained_methods.push_back(kReconMethod);
    if (on(12)) facts.evaluated_methods = facts.trained_methods;
    facts.report_written = on(13);
    if (on(14)) facts.taught_elsewhere = "Taught in the simulated cell, recorded there";
    SCOPED_TRACE("facts bits " + std::to_string(bits));

    const std::vector<StepStatus> steps = EvaluateWorkflow(facts);
    const Step next = NextStep(facts);
    EXPECT_NE(steps[static_cast<int>(next)].state, StepState::kBlocked);
    EXPECT_NE(steps[static_cast<int>(Step::kCell)].state, StepState::kBlocked);
    for (const StepStatus& status : steps) {
      if (static_cast<int>(status.step) <= static_cast<int>(next)) {
        EXPECT_TRUE(CanOpen(facts, status.step)) << StepTitle(status.step);
      }
      if (status.state != StepState::kBlocked) {
        EXPECT_TRUE(CanOpen(facts, status.step));
        EXPECT_THAT(status.why_blocked, IsEmpty());
        continue;
      }
      ++blocked_seen;
      bool names_a_step = false;
      for (Step other : kAllSteps) {
        if (other != status.step && status.why_blocked.ends_with(StepTag(other))) {
          names_a_step = true;
        }
      }
      EXPECT_TRUE(names_a_step) << StepTitle(status.step) << ": " << status.why_blocked;
    }
  }
  EXPECT_GT(blocked_seen, 0);
}

}  // namespace
}  // namespace recon::teach
