// The studio's screens, headless: a golden screenshot of every workflow step, and the commands
// that clicking its controls sends. The snapshots come from workflow facts (studio_test_support.h),
// so these tests need no cell, no session and no training.

#include <gtest/gtest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include <map>
#include <optional>
#include <variant>

#include "engine/core/error.h"
#include "tests/support/golden_image.h"
#include "tests/ui/studio_harness.h"
#include "tests/ui/studio_test_support.h"
#include "ui/platform/frame_input.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"
#include "ui/widgets/widget_registry.h"

namespace recon::ui {
namespace {

using testing::Progress;
using testing::SnapshotAt;

struct ScreenCase {
  const char* name;
  Progress progress;
  teach::Step step;
};

class StudioScreenTest : public ::testing::TestWithParam<ScreenCase> {};

TEST_P(StudioScreenTest, MatchesItsGolden) {
  const ScreenCase& c = GetParam();
  StudioHarness harness;
  harness.Show(SnapshotAt(c.progress, c.step));
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath(c.name)));
}

// A high-DPI screen: --ui-scale 2 on a 2560 x 1600 window draws the 1280 x 800 layout twice as
// large (the font, paddings and every size the screens give through Px).
TEST(StudioScreenTest, TheRecordScreenAtUiScale2MatchesItsGolden) {
  StudioHarness harness(2560, 1600, 2.0f);
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("record_2560x1600_scale2")));
  harness.driver().Click("Start recording");  // the click targets scale with what is drawn
  ASSERT_EQ(harness.Commands().size(), 1u);
}

// The smallest window the studio supports, 1024 x 640: the camera views shrink, tables scroll
// sideways instead of clipping, and both rollout panels stay on screen.
TEST_P(StudioScreenTest, MatchesItsGoldenAt1024x640) {
  const ScreenCase& c = GetParam();
  StudioHarness harness(1024, 640);
  harness.Show(SnapshotAt(c.progress, c.step));
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath(std::string(c.name) + "_1024x640")));
}

INSTANTIATE_TEST_SUITE_P(
    EveryStep, StudioScreenTest,
    ::testing::Values(ScreenCase{"cell_empty", Progress::kNothing, teach::Step::kCell},
                      ScreenCase{"cell", Progress::kCellUp, teach::Step::kCell},
                      ScreenCase{"beacons", Progress::kCellUp, teach::Step::kBeacons},
                      ScreenCase{"calibrate", Progress::kCalibrated, teach::Step::kCalibrate},
                      ScreenCase{"record", Progress::kRecorded, teach::Step::kRecord},
                      ScreenCase{"play", Progress::kRecorded, teach::Step::kPlay},
                      ScreenCase{"train", Progress::kTrained, teach::Step::kTrain},
                      ScreenCase{"rollouts", Progress::kDone, teach::Step::kRollouts},
                      ScreenCase{"report", Progress::kDone, teach::Step::kReport}),
    [](const ::testing::TestParamInfo<ScreenCase>& param) {
      return std::string(param.param.name);
    });

TEST(StudioScreenTest, TheEmergencyStopShowsOnEveryScreenAndMatchesItsGolden) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  s.safety.estop = true;
  s.safety.estop_reason = "e-stop button";
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("estop")));
}

TEST(StudioCommandTest, TheEStopButtonAndF12EngageItAndReleaseReleasesIt) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.driver().Click("E-STOP (F12)");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<EmergencyStop>(commands[0]));
  EXPECT_TRUE(std::get<EmergencyStop>(commands[0]).engage);

  harness.driver().Press(kEmergencyStopKey);
  commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<EmergencyStop>(commands[0]));
  EXPECT_TRUE(std::get<EmergencyStop>(commands[0]).engage);
  EXPECT_EQ(std::get<EmergencyStop>(commands[0]).reason, "F12 pressed");

  StudioSnapshot stopped = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  stopped.safety.estop = true;
  stopped.safety.estop_reason = "F12 pressed";
  harness.Show(stopped);
  harness.Commands();
  EXPECT_THROW(harness.driver().Click("E-STOP (F12)"), UserError);     // replaced by Release
  EXPECT_THROW(harness.driver().Click("Start recording"), UserError);  // disabled until then
  harness.driver().Press(kEmergencyStopKey);  // already engaged: nothing new to say
  EXPECT_TRUE(harness.Commands().empty());
  harness.driver().Click("Release e-stop");
  commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<EmergencyStop>(commands[0]));
  EXPECT_FALSE(std::get<EmergencyStop>(commands[0]).engage);
}

TEST(StudioCommandTest, TheCellScreenListsWhatIsPluggedInAndRescans) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kCellUp, teach::Step::kCell));
  harness.driver().Click("Rescan");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<RescanDevices>(commands[0]));
}

TEST(StudioCommandTest, ClickingAStepOpensItAndABlockedStepDoesNothing) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kCellUp, teach::Step::kCell));
  harness.driver().Click("Beacons##step");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<OpenStep>(commands[0]));
  EXPECT_EQ(std::get<OpenStep>(commands[0]).step, teach::Step::kBeacons);
  // Train is blocked until demonstrations exist: its row is disabled and sends nothing.
  EXPECT_THROW(harness.driver().Click("Train##step"), UserError);
  EXPECT_TRUE(harness.Commands().empty());
}

TEST(StudioCommandTest, ClickingTheObjectInTheCameraAssignsTheBeacon) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kCellUp, teach::Step::kBeacons));
  harness.driver().Click("object:plate");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_FALSE(commands.empty());
  ASSERT_TRUE(std::holds_alternative<AssignBeacon>(commands[0]));
  EXPECT_EQ(std::get<AssignBeacon>(commands[0]).beacon, "plate");
  EXPECT_EQ(std::get<AssignBeacon>(commands[0]).object, "plate");
}

TEST(StudioCommandTest, RecordScreenSendsRecordingAndEpisodeCommands) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.driver().Click("Start recording");
  harness.driver().Click("Delete##demo_1");
  harness.driver().Click("Good##demo_2");  // demo_2 is marked bad in the snapshot
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<StartRecording>(commands[0]));
  ASSERT_TRUE(std::holds_alternative<DeleteEpisode>(commands[1]));
  EXPECT_EQ(std::get<DeleteEpisode>(commands[1]).name, "demo_1");
  ASSERT_TRUE(std::holds_alternative<MarkEpisodeBad>(commands[2]));
  EXPECT_EQ(std::get<MarkEpisodeBad>(commands[2]).name, "demo_2");
  EXPECT_FALSE(std::get<MarkEpisodeBad>(commands[2]).bad);
}

TEST(StudioCommandTest, AScriptDrivesTheStudioAndNamesItsMistakes) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kTrain));
  harness.driver().RunScript("# train both\nwait 2\nclick Train Baseline and RECON\n");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<StartTraining>(commands[0]));
  EXPECT_EQ(std::get<StartTraining>(commands[0]).methods,
            (std::vector<std::string>{"baseline", "recon"}));
  EXPECT_EQ(std::get<StartTraining>(commands[0]).steps, 0) << "the world's recipe decides";
  try {
    harness.driver().RunScript("wait 1\nclick Trian\n", "demo.script");
    FAIL() << "a misspelt label must be an error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("demo.script:2: no widget labelled 'Trian'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(harness.driver().RunScript("jump 3\n"), UserError);
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

TEST(StudioCommandTest, TheTeleopIsChosenOnTheRecordScreenAndAMissingGamepadSaysWhy) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.driver().Click("[ ] Keyboard##teleop");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<SetTeleopMode>(commands[0]));
  EXPECT_EQ(std::get<SetTeleopMode>(commands[0]).mode, TeleopMode::kKeyboard);
  try {
    harness.driver().Click("[ ] Gamepad##teleop");
    FAIL() << "the gamepad is not connected; its button must be disabled";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("disabled"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(harness.Commands().empty());
}

TEST(StudioCommandTest, TheSessionMenuAndPickerOpenSessions) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.driver().Click("Session");
  harness.driver().Click("Open or create...");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<ShowSessionPicker>(commands[0]));
  EXPECT_TRUE(std::get<ShowSessionPicker>(commands[0]).show);

  // A recent session from the menu.
  harness.driver().WaitFrames(2);
  harness.driver().Click("Session");
  harness.driver().Click("/home/lab/sessions/cups##recent-menu");
  commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<OpenSession>(commands[0]));
  EXPECT_EQ(std::get<OpenSession>(commands[0]).dir, "/home/lab/sessions/cups");

  // The picker: type a folder and open it.
  StudioSnapshot picking = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  picking.picking_session = true;
  harness.Show(picking);
  EXPECT_THROW(harness.driver().Click("Open or create"), UserError);  // nothing typed yet
  harness.driver().Click("##session-folder");
  harness.driver().Type("/tmp/new-session");
  harness.driver().WaitFrames(2);
  harness.driver().Click("Open or create");
  commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<OpenSession>(commands[0]));
  EXPECT_EQ(std::get<OpenSession>(commands[0]).dir, "/tmp/new-session");
  harness.driver().Click("Cancel##session-picker");
  commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_FALSE(std::get<ShowSessionPicker>(commands[0]).show);
}

TEST(StudioCommandTest, PlayDataCanBeStoppedWhileItRecords) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kPlay);
  s.recording_play = true;
  s.play_recorded = 12;
  s.play_target = 30;
  harness.Show(s);
  harness.driver().Click("Stop");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<StopPlay>(commands[0]));
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

TEST(StudioCommandTest, KeysDriveTheArmWhileAKeyboardDemonstrationRecords) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  s.teleop = TeleopMode::kKeyboard;
  s.recording = true;
  harness.Show(s);
  harness.driver().RunScript("hold right 0.05\nhold pageup 0.05\npress space\npress enter\n");
  const std::vector<StudioCommand> commands = harness.Commands();
  bool right = false, up = false, grip = false, stop = false;
  for (const StudioCommand& c : commands) {
    if (const auto* input = std::get_if<TeleopInput>(&c)) {
      right |= input->screen_right == 1 && input->screen_up == 0 && input->raise == 0;
      up |= input->raise == 1 && input->screen_right == 0;
    }
    grip |= std::holds_alternative<ToggleGripper>(c);
    stop |= std::holds_alternative<StopRecording>(c);
  }
  EXPECT_TRUE(right) << "the right arrow";
  EXPECT_TRUE(up) << "page up";
  EXPECT_TRUE(grip) << "space";
  EXPECT_TRUE(stop) << "enter";
  // The same keys with the scripted teacher recording send nothing: while a demonstration
  // records, the arrows do not move the keyboard focus to a button that Space would then press.
  s.teleop = TeleopMode::kScripted;
  harness.Show(s);
  harness.Commands();
  harness.driver().RunScript("hold right 0.05\npress space\n");
  EXPECT_TRUE(harness.Commands().empty());
  EXPECT_THROW(harness.driver().RunScript("hold right\n"), UserError);
  EXPECT_THROW(harness.driver().RunScript("hold sideways 1\n"), UserError);
}

// The snapshot lags the commands (here it never catches up): Space then Page Up at once toggles
// the gripper once and never sends it back, and a key tapped and let go before the controller
// has shown it still stops the arm.
TEST(StudioCommandTest, KeysAreSentWhateverTheSnapshotHasCaughtUpWith) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  s.teleop = TeleopMode::kKeyboard;
  s.recording = true;
  harness.Show(s);
  harness.Commands();
  harness.driver().RunScript("press space\nhold pageup 0.05\n");
  const std::vector<StudioCommand> commands = harness.Commands();
  int toggles = 0;
  std::vector<TeleopInput> inputs;
  for (const StudioCommand& c : commands) {
    toggles += std::holds_alternative<ToggleGripper>(c) ? 1 : 0;
    if (const auto* input = std::get_if<TeleopInput>(&c)) inputs.push_back(*input);
  }
  EXPECT_EQ(toggles, 1);
  ASSERT_GE(inputs.size(), 2u);
  EXPECT_EQ(inputs.front().raise, 1) << "page up";
  EXPECT_EQ(inputs.back(), TeleopInput{}) << "let go: the arm stops";
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

TEST(StudioCommandTest, RolloutPlaybackStepsScenesAndFrames) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kDone, teach::Step::kRollouts));
  harness.driver().RunScript(
      "click Scene >\nclick < Scene\nclick >##step\nclick <##step-back\nclick |<\nclick >|\n"
      "click Play\n");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 7u);
  const auto frame = [&](size_t i) { return std::get<ShowRolloutFrame>(commands.at(i)); };
  EXPECT_EQ(frame(0).scenario, 3);  // the snapshot shows scene index 2, step 42 of 201
  EXPECT_EQ(frame(0).frame, 0);
  EXPECT_EQ(frame(1).scenario, 1);
  EXPECT_EQ(frame(2).scenario, 2);
  EXPECT_EQ(frame(2).frame, 43);
  EXPECT_EQ(frame(3).frame, 41);
  EXPECT_EQ(frame(4).frame, 0);
  EXPECT_EQ(frame(5).frame, 200);
  ASSERT_TRUE(std::holds_alternative<PlayRollouts>(commands[6]));
  EXPECT_TRUE(std::get<PlayRollouts>(commands[6]).playing);
  // While rollouts run, the playback waits.
  StudioSnapshot running = SnapshotAt(Progress::kDone, teach::Step::kRollouts);
  running.rollouts_running = true;
  harness.Show(running);
  harness.Commands();
  EXPECT_THROW(harness.driver().Click("Play"), UserError);
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

// Escape closes a menu (ImGui's own meaning) and never stops the arm; only F12 and the button do.
TEST(StudioCommandTest, EscapeClosesAMenuAndNeverEngagesTheEStop) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.driver().Click("Session");
  EXPECT_TRUE(harness.driver().Drawn("Open or create...")) << "the menu opened";
  harness.driver().Press(ImGuiKey_Escape);
  harness.driver().WaitFrames(2);
  EXPECT_FALSE(harness.driver().Drawn("Open or create...")) << "Escape closed the menu";
  harness.driver().Press(ImGuiKey_Escape);  // and on its own, with nothing open
  for (const StudioCommand& c : harness.Commands()) {
    EXPECT_FALSE(std::holds_alternative<EmergencyStop>(c)) << "Escape engaged the e-stop";
  }
}

// A training that has started but not yet reported a step (it loads the session's data first)
// is running: the screen offers Cancel, never a second "Train"; after Cancel it says it is
// stopping and does not take a second click.
TEST(StudioCommandTest, TheTrainScreenFollowsTheJobNotTheProgressBars) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kTrain);
  s.training_running = true;
  s.busy_with = "the training";
  harness.Show(s);
  EXPECT_FALSE(harness.driver().Drawn("Train Baseline and RECON"));
  harness.driver().Click("Cancel training");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<CancelTraining>(commands[0]));

  s.training_cancelling = true;
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Cancelling...##cancel-training"), UserError);
  EXPECT_TRUE(harness.Commands().empty());

  // Once it has ended, the saved models are shown, with why one no longer matches the session.
  StudioSnapshot ended = SnapshotAt(Progress::kTrained, teach::Step::kTrain);
  TrainingView saved;
  saved.method = "baseline";
  saved.label = "Baseline";
  saved.done = true;
  saved.step = saved.steps = 7500;
  saved.out_of_date = "trained on 4 episodes; since then demo_4 was added";
  ended.training = {saved};
  harness.Show(ended);
  EXPECT_TRUE(harness.driver().Drawn("Train Baseline and RECON"));
  EXPECT_FALSE(harness.driver().Drawn("Cancel training"));
}

// Rollouts show how far they are and can be cancelled, once.
TEST(StudioCommandTest, RunningRolloutsShowProgressAndCancel) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kTrained, teach::Step::kRollouts);
  s.rollouts_running = true;
  s.rollout_steps_done = 120;
  s.rollout_steps_total = 400;
  s.busy_with = "the rollouts";
  harness.Show(s);
  EXPECT_FALSE(harness.driver().Drawn("Run rollouts"));
  harness.driver().Click("Cancel rollouts");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<CancelRollouts>(commands[0]));
  s.rollouts_cancelling = true;
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Cancelling...##cancel-rollouts"), UserError);
  EXPECT_TRUE(harness.Commands().empty());
}

// While something runs the session cannot change; the menu's items are disabled (a click does
// nothing) and the menu says why.
TEST(StudioCommandTest, TheSessionMenuIsDisabledWhileAJobRuns) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kTrain);
  s.training_running = true;
  s.busy_with = "the training";
  harness.Show(s);
  harness.driver().Click("Session");
  EXPECT_THROW(harness.driver().Click("Open or create..."), UserError);
  EXPECT_THROW(harness.driver().Click("/home/lab/sessions/cups##recent-menu"), UserError);
  EXPECT_TRUE(harness.Commands().empty());
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

// Session > Quit asks the application to close; with something running it says what stops.
TEST(StudioCommandTest, TheSessionMenuHasQuit) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.driver().Click("Session");
  harness.driver().Click("Quit");
  std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<Quit>(commands[0]));

  StudioSnapshot training = SnapshotAt(Progress::kRecorded, teach::Step::kTrain);
  training.training_running = true;
  training.busy_with = "the training";
  harness.Show(training);
  harness.driver().WaitFrames(2);
  harness.driver().Click("Session");
  harness.driver().Click("Quit (stops the training)##quit");
  commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<Quit>(commands[0]));
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

// A take shows its time limit, warns in its last 5 s, and once set aside unfinished waits for
// Keep or Discard with nothing else on the list clickable.
TEST(StudioCommandTest, ATakeShowsItsLimitAndAnUnfinishedOneWaitsForKeepOrDiscard) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  s.teleop = TeleopMode::kKeyboard;
  s.recording = true;
  s.recording_samples = 170;
  s.recording_max_samples = 200;
  s.recording_step_s = 0.1;
  harness.Show(s);
  EXPECT_TRUE(harness.driver().Drawn("Stop and keep"));

  StudioSnapshot pending = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  pending.pending_take = "The take reached its 20 s limit before the task was done";
  harness.Show(pending);
  harness.Commands();
  EXPECT_THROW(harness.driver().Click("Start recording"), UserError);  // there, disabled
  EXPECT_THROW(harness.driver().Click("Delete##demo_0"), UserError);
  harness.driver().Click("Keep as not done");
  harness.driver().Click("Discard##take");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<StopRecording>(commands[0]));
  EXPECT_TRUE(std::holds_alternative<DiscardRecording>(commands[1]));
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

TEST(StudioCommandTest, AnUndoBringsTheLastDeletedEpisodeBack) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  EXPECT_FALSE(harness.driver().Drawn("Undo delete demo_2##undo-delete"));
  s.undo_delete = "demo_2";
  harness.Show(s);
  harness.driver().Click("Undo delete demo_2##undo-delete");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<UndoDelete>(commands[0]));
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

TEST(StudioCommandTest, AWrittenReportOpensInTheBrowser) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kDone, teach::Step::kReport);
  s.report_path.clear();
  harness.Show(s);
  EXPECT_FALSE(harness.driver().Drawn("Open in browser"));
  s.report_path = "sessions/toast/report/report.html";
  harness.Show(s);
  harness.driver().Click("Open in browser");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<OpenReport>(commands[0]));
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

/// The last SetTeacherView among `commands`, if any.
std::optional<SetTeacherView> LastViewCommand(const std::vector<StudioCommand>& commands) {
  std::optional<SetTeacherView> last;
  for (const StudioCommand& c : commands) {
    if (const auto* view = std::get_if<SetTeacherView>(&c)) last = *view;
  }
  return last;
}

// Dragging the 3-D view sideways turns it around the table, dragging it down looks from higher
// up, the wheel steps closer, and the presets jump to a side, the front or above. Each drag is
// measured from where it started, so a snapshot that lags the commands loses nothing.
TEST(StudioCommandTest, TheTeachersViewTurnsWhenDraggedAndZoomsWithTheWheel) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.Commands();
  harness.driver().Drag("teacher-view", 50, 0);
  std::optional<SetTeacherView> view = LastViewCommand(harness.Commands());
  ASSERT_TRUE(view.has_value());
  EXPECT_NEAR(view->azimuth_deg, 90 - 50 * 0.4, 1e-3);
  EXPECT_NEAR(view->elevation_deg, -35, 1e-3);
  EXPECT_NEAR(view->distance_m, 1.3, 1e-6);

  harness.driver().Drag("teacher-view", 0, 25);
  view = LastViewCommand(harness.Commands());
  ASSERT_TRUE(view.has_value());
  EXPECT_NEAR(view->azimuth_deg, 90, 1e-3);
  EXPECT_NEAR(view->elevation_deg, -35 - 25 * 0.4, 1e-3);

  harness.driver().Scroll("teacher-view", 1);
  view = LastViewCommand(harness.Commands());
  ASSERT_TRUE(view.has_value());
  EXPECT_NEAR(view->distance_m, 1.3 * 0.9, 1e-5);

  harness.driver().Click("Front##view");
  view = LastViewCommand(harness.Commands());
  ASSERT_TRUE(view.has_value());
  EXPECT_EQ(view->azimuth_deg, 180);
  EXPECT_EQ(view->elevation_deg, -40);
  // A real cell has no 3-D view: the camera takes its place, and nothing turns.
  StudioSnapshot real = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  real.teacher_view = {};
  harness.Show(real);
  EXPECT_FALSE(harness.driver().Drawn("teacher-view"));
  EXPECT_TRUE(harness.driver().Drawn("camera##record"));
}

// What the grip does is said in words, and each state of it draws (a golden each for the two a
// teacher must tell apart).
TEST(StudioScreenTest, TheGripStateAndTheKeyMappingsShowOnTheRecordScreen) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  s.teleop = TeleopMode::kKeyboard;
  s.grip_m[2] = 0.009f;
  s.gripper_closed = true;
  s.grip.state = GripState::kHolding;
  harness.Show(s);
  EXPECT_TRUE(
      ::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("record_holding")));
  s.grip.state = GripState::kClosedOnNothing;
  s.grip_m[2] = 0.04f;
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("record_closed_on_nothing")));
}

// keyboard-take gives a take only while one runs with the keyboard, and says so otherwise.
TEST(StudioCommandTest, AKeyboardTakeNeedsAKeyboardTakeRunning) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  harness.Show(s);
  EXPECT_THROW(harness.driver().RunScript("keyboard-take 5\n"), UserError);  // no snapshot source
  harness.driver().SetSnapshotSource([&] { return s; });
  try {
    harness.driver().RunScript("keyboard-take 5\n");
    ADD_FAILURE() << "a keyboard take ran with no take recording";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("no keyboard take is running"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

/// Where every labelled widget of the last frame was drawn.
std::map<std::string, WidgetRect> Layout() {
  std::map<std::string, WidgetRect> layout;
  const WidgetRegistry& registry = WidgetRegistry::ForThisThread();
  for (const std::string& label : registry.Labels()) layout[label] = *registry.Find(label);
  return layout;
}

/// Shows each snapshot in turn: every widget drawn both before and after a change stays where
/// it was, so a click aimed at it as the state changes lands on it.
void ExpectNothingMoves(const std::vector<std::pair<std::string, StudioSnapshot>>& states) {
  StudioHarness harness;
  harness.Show(states[0].second);
  std::map<std::string, WidgetRect> before = Layout();
  for (size_t i = 1; i < states.size(); ++i) {
    harness.Show(states[i].second);
    const std::map<std::string, WidgetRect> after = Layout();
    int common = 0;
    for (const auto& [label, rect] : before) {
      const auto it = after.find(label);
      if (it == after.end()) continue;
      ++common;
      EXPECT_NEAR(it->second.min_x, rect.min_x, 0.5) << states[i].first << ": " << label;
      EXPECT_NEAR(it->second.min_y, rect.min_y, 0.5) << states[i].first << ": " << label;
    }
    EXPECT_GE(common, 5) << states[i].first;
    before = after;
  }
}

// The keyboard is chosen, a take starts, counts down, runs, ends unfinished, is kept; the grip
// opens, closes on nothing, holds: what stays on the Record screen stays put.
TEST(StudioLayoutTest, NothingMovesOnTheRecordScreenAsATakeRuns) {
  const StudioSnapshot scripted = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  StudioSnapshot idle = scripted;
  idle.teleop = TeleopMode::kKeyboard;
  StudioSnapshot countdown = idle;
  countdown.recording = true;
  countdown.countdown_s = 2.5;
  countdown.busy_with = "the recording";
  StudioSnapshot running = countdown;
  running.countdown_s = 0;
  running.recording_samples = 40;
  running.recording_max_samples = 200;
  running.grip_m[2] = 0.02f;
  StudioSnapshot low = running;
  low.grip_m[2] = 0.009f;
  StudioSnapshot closing = low;
  closing.gripper_closed = true;
  closing.grip.state = GripState::kClosing;
  StudioSnapshot missed = closing;
  missed.grip.state = GripState::kClosedOnNothing;
  StudioSnapshot holding = closing;
  holding.grip.state = GripState::kHolding;
  StudioSnapshot last_seconds = holding;
  last_seconds.recording_samples = 170;
  StudioSnapshot pending = idle;
  pending.pending_take = "The take reached its 20 s limit without the task done";
  StudioSnapshot kept = idle;
  kept.episodes.push_back({"demo_4", 200, 20.0, false, false, "train", ""});
  ExpectNothingMoves({{"scripted", scripted},
                      {"keyboard chosen", idle},
                      {"countdown", countdown},
                      {"running", running},
                      {"low", low},
                      {"closing", closing},
                      {"closed on nothing", missed},
                      {"holding", holding},
                      {"last seconds", last_seconds},
                      {"pending", pending},
                      {"kept", kept}});
}

// An error arrives while a teacher works (a failed save, a device gone): it is shown without
// pushing the screen's controls down under the pointer.
TEST(StudioLayoutTest, AnErrorArrivingMovesNothing) {
  for (const teach::Step step :
       {teach::Step::kRecord, teach::Step::kTrain, teach::Step::kRollouts, teach::Step::kCell}) {
    StudioSnapshot quiet = SnapshotAt(Progress::kDone, step);
    StudioSnapshot failed = quiet;
    failed.errors = {"cannot save demo_4: No space left on device (/data/sessions/toast)",
                     "the gamepad was unplugged; the arm holds still"};
    ExpectNothingMoves({{"quiet", quiet}, {"an error", failed}, {"dismissed", quiet}});
  }
  StudioHarness harness;
  StudioSnapshot failed = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  failed.errors = {"cannot save demo_4: No space left on device (/data/sessions/toast)"};
  harness.Show(failed);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("errors")));
  harness.driver().Click("Dismiss");
  const std::vector<StudioCommand> commands = harness.Commands();
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<DismissErrors>(commands[0]));
}

// Training and rollouts start, run, are cancelled and end: the screens' controls stay put.
TEST(StudioLayoutTest, NothingMovesAsTrainingAndRolloutsRun) {
  StudioSnapshot train_idle = SnapshotAt(Progress::kTrained, teach::Step::kTrain);
  StudioSnapshot training = train_idle;
  training.training_running = true;
  training.busy_with = "the training";
  StudioSnapshot cancelling = training;
  cancelling.training_cancelling = true;
  ExpectNothingMoves({{"idle", train_idle},
                      {"training", training},
                      {"cancelling", cancelling},
                      {"done", train_idle}});

  StudioSnapshot rollouts_idle = SnapshotAt(Progress::kDone, teach::Step::kRollouts);
  StudioSnapshot rolling = rollouts_idle;
  rolling.rollouts_running = true;
  rolling.rollout_steps_done = 120;
  rolling.rollout_steps_total = 400;
  rolling.busy_with = "the rollouts";
  ExpectNothingMoves({{"idle", rollouts_idle}, {"running", rolling}, {"done", rollouts_idle}});
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

bool TooltipShown() {
  const ImGuiWindow* tooltip = ImGui::FindWindowByName("##Tooltip_00");
  return tooltip != nullptr && tooltip->Active;
}

// A disabled button says why once the pointer is moved onto it and rests; a button that turns
// disabled under a pointer that stayed where it clicked (Start recording as the take counts
// down) raises no tooltip over what the click brought up.
TEST(StudioCommandTest, ADisabledButtonSaysWhyOnlyWhenThePointerComesToIt) {
  StudioHarness harness;
  StudioSnapshot idle = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  idle.teleop = TeleopMode::kKeyboard;
  StudioSnapshot countdown = idle;
  countdown.recording = true;
  countdown.countdown_s = 2.5;
  harness.Show(idle);
  harness.driver().Click("Start recording");
  harness.Show(countdown);
  harness.driver().WaitFrames(60);  // 1 s
  EXPECT_FALSE(TooltipShown());
  harness.driver().PointAt("Discard##take");    // the pointer goes elsewhere...
  harness.driver().PointAt("Start recording");  // ...and comes back
  harness.driver().WaitFrames(40);
  EXPECT_TRUE(TooltipShown());
}

}  // namespace
}  // namespace recon::ui
