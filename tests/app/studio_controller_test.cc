// The studio's engine side without a window: the controller's cell thread with the real
// simulated cell and real session files. Teleop from the keyboard, play data sample by sample,
// switching sessions and the list of recent ones, and what the teacher sees of the devices.

#include "app/studio/studio_controller.h"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <linux/joystick.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "app/cli/session_summary.h"
#include "app/cli/session_world.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/store/session.h"
#include "engine/teach/recorder.h"
#include "engine/teach/session_setup.h"
#include "engine/worlds/world_factory.h"
#include "tests/app/controller_wait.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class StudioControllerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("recon-controller-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  StudioOptions Options(const std::string& session = "session") const {
    StudioOptions options;
    options.session_dir = session.empty() ? "" : (dir_ / session).string();
    options.recent_sessions_file = (dir_ / "config" / "recent.json").string();
    options.real_time = false;
    options.countdown_s = 0;  // a person's take starts at once (the countdown has its own test)
    return options;
  }

  /// Polls the controller's snapshots until `done` holds; fails the test after `timeout_s`.
  static ui::StudioSnapshot WaitFor(const StudioController& controller,
                                    const std::function<bool(const ui::StudioSnapshot&)>& done,
                                    double timeout_s = 60) {
    return testing::WaitForSnapshot(controller, done, timeout_s);
  }
  static void WaitSettled(const StudioController& controller) {
    WaitFor(controller, [](const ui::StudioSnapshot&) { return true; });
    // One more published snapshot after the last command.
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
  }

  fs::path dir_;
};

// The arrows move the arm the way the teacher's 3-D view shows it (turn the view, and they turn
// with it), Page Down lowers it, Space closes the gripper, and Stop keeps the demonstration as a
// keyboard-teleop episode.
TEST_F(StudioControllerTest, TheKeyboardDrivesTheArmAsTheTeachersViewShowsIt) {
  auto owner = std::make_unique<StudioController>(Options());
  StudioController& controller = *owner;
  controller.Push(ui::OpenStep{teach::Step::kRecord});  // where the 3-D view is drawn
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  controller.Push(ui::StartRecording{});
  ui::StudioSnapshot s = WaitFor(
      controller, [](const auto& now) { return now.recording && now.teacher_view.available; });
  ASSERT_EQ(s.teleop, ui::TeleopMode::kKeyboard);
  const std::array<float, 2> start_pixel = s.teacher_view.spot_pixel;
  const std::array<float, 3> start = s.grip_m;

  ui::TeleopInput right;
  right.screen_right = 1;
  controller.Push(right);
  s = WaitFor(
      controller,
      [&](const auto& now) { return now.teacher_view.spot_pixel[0] > start_pixel[0] + 20; }, 20);
  EXPECT_GT(s.teacher_view.spot_pixel[0], start_pixel[0] + 20);
  EXPECT_NEAR(s.teacher_view.spot_pixel[1], start_pixel[1], 6) << "right must not drift up or down";
  EXPECT_NEAR(s.grip_m[2], start[2], 0.01);

  // Turned to look from the front, the same key moves the arm to that view's right: along the
  // table's +y instead of its +x.
  controller.Push(ui::TeleopInput{});
  controller.Push(ui::SetTeacherView{180, -40, 1.4f});
  s = WaitFor(controller, [](const auto& now) { return now.teacher_view.azimuth_deg == 180; });
  const std::array<float, 3> before_turned = s.grip_m;
  controller.Push(right);
  s = WaitFor(
      controller, [&](const auto& now) { return now.grip_m[1] > before_turned[1] + 0.04; }, 20);
  EXPECT_GT(s.grip_m[1], before_turned[1] + 0.04);
  EXPECT_NEAR(s.grip_m[0], before_turned[0], 0.015) << "along +y only";

  ui::TeleopInput lower;
  lower.raise = -1;
  controller.Push(lower);
  controller.Push(ui::ToggleGripper{});
  const float before_lowering = s.grip_m[2];
  s = WaitFor(
      controller, [&](const auto& now) { return now.grip_m[2] < before_lowering - 0.05; }, 20);
  EXPECT_TRUE(s.gripper_closed);
  EXPECT_TRUE(s.recording) << "a keyboard demonstration runs until the teacher stops it";

  controller.Push(ui::TeleopInput{});
  controller.Push(ui::StopRecording{});
  s = WaitFor(controller, [](const auto& now) { return !now.recording && !now.episodes.empty(); });
  ASSERT_EQ(s.episodes.size(), 1u);
  EXPECT_FALSE(s.episodes[0].succeeded);
  EXPECT_GT(s.episodes[0].samples, 5);
  // A gamepad that is not plugged in is refused.
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kGamepad});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors[0], HasSubstr("no gamepad connected"));
  const std::string session = s.session_dir;
  EXPECT_TRUE(fs::exists(fs::path(session) / "episodes" / "demo_0.h5"));
  owner.reset();  // closes the session
  const store::Session opened = store::Session::Open(session, store::Session::Access::kReadOnly);
  ASSERT_EQ(opened.demos().size(), 1u);
  EXPECT_EQ(opened.demos()[0].meta.source, "keyboard-teleop");
}

// Fine control: a key tapped and let go at once moves one small step, even when both happen
// between two control periods; Home/End turn the wrist, and the readout follows the turn.
TEST_F(StudioControllerTest, ATapMovesAStepAndTheWristTurns) {
  StudioController controller(Options());
  controller.Push(ui::OpenStep{teach::Step::kRecord});
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  controller.Push(ui::StartRecording{});
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) {
    return now.recording && now.countdown_s <= 0 && now.recording_samples > 2;
  });
  const float start_z = s.grip_m[2];
  ui::TeleopInput lower;
  lower.raise = -1;
  controller.Push(lower);
  controller.Push(ui::TeleopInput{});
  s = WaitFor(
      controller, [&](const auto& now) { return now.grip_m[2] < start_z - 0.001f; }, 10);
  // Let the servo settle, then measure the step.
  const int after = s.recording_samples + 5;
  s = WaitFor(
      controller, [&](const auto& now) { return now.recording_samples >= after; }, 10);
  const float step_m = start_z - s.grip_m[2];
  EXPECT_GT(step_m, 0.0015f);
  EXPECT_LT(step_m, 0.006f) << "a tap is a small step, not a centimetre or two";

  EXPECT_NEAR(s.grip.wrist_turn_deg, 0.0f, 1.0f);
  const std::array<float, 4> jaw_before = s.teacher_view.jaw_pixels;
  ui::TeleopInput turn;
  turn.turn = 1;
  controller.Push(turn);
  s = WaitFor(
      controller, [](const auto& now) { return now.grip.wrist_turn_deg > 30; }, 20);
  controller.Push(ui::TeleopInput{});
  EXPECT_GT(s.grip.wrist_turn_deg, 30.0f);
  EXPECT_EQ(s.grip.wrist_limit_deg, 90.0f);
  s = WaitFor(controller,
              [&](const auto& now) { return now.teacher_view.jaw_pixels != jaw_before; });
  EXPECT_NE(s.teacher_view.jaw_pixels, jaw_before) << "the jaw's axis turns in the 3-D view";
  controller.Push(ui::DiscardRecording{});
}

// What the screen shows before Start is the scene the take is recorded in (the paper's protocol
// gives two takes one configuration), also after a take is discarded or an episode deleted; and
// a discarded take leaves the arm at home with the gripper open, not closed on nothing.
TEST_F(StudioControllerTest, TheSceneBeforeStartIsTheTakesScene) {
  StudioController controller(Options());
  controller.Push(ui::OpenStep{teach::Step::kBeacons});  // where the camera view is drawn
  const auto plate = [](const ui::StudioSnapshot& s) {
    for (const ui::ObjectView& o : s.objects) {
      if (o.name == "plate") return std::array<float, 2>{o.pixel_x, o.pixel_y};
    }
    return std::array<float, 2>{-1, -1};
  };
  const auto bowl = [](const ui::StudioSnapshot& s) {
    for (const ui::ObjectView& o : s.objects) {
      if (o.name == "bowl") return std::array<float, 2>{o.pixel_x, o.pixel_y};
    }
    return std::array<float, 2>{-1, -1};
  };
  controller.Push(ui::StartRecording{});  // demo_0, scripted
  WaitFor(controller, [](const auto& now) { return !now.recording && !now.episodes.empty(); });
  for (int round = 0; round < 2; ++round) {
    // Before Start: the scene of demo_1, the second take of configuration 0.
    ui::StudioSnapshot before = WaitFor(controller, [&](const auto& now) {
      return !now.objects.empty() && now.episodes.size() == 1;
    });
    controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
    controller.Push(ui::StartRecording{});
    ui::StudioSnapshot during = WaitFor(controller, [](const auto& now) {
      return now.recording && now.countdown_s <= 0 && now.recording_samples > 0;
    });
    EXPECT_NEAR(plate(during)[0], plate(before)[0], 1.0f) << "round " << round;
    EXPECT_NEAR(plate(during)[1], plate(before)[1], 1.0f) << "round " << round;
    EXPECT_NEAR(bowl(during)[0], bowl(before)[0], 1.0f) << "round " << round;
    EXPECT_NEAR(bowl(during)[1], bowl(before)[1], 1.0f) << "round " << round;
    ui::TeleopInput lower;
    lower.raise = -1;
    controller.Push(lower);
    controller.Push(ui::ToggleGripper{});
    WaitFor(controller, [](const auto& now) { return now.gripper_closed; });
    controller.Push(ui::TeleopInput{});
    controller.Push(ui::DiscardRecording{});
    ui::StudioSnapshot after = WaitFor(controller, [](const auto& now) { return !now.recording; });
    after = WaitFor(controller, [](const auto& now) { return !now.gripper_closed; });
    EXPECT_EQ(after.grip.state, ui::GripState::kOpen) << "round " << round;
    controller.Push(ui::SetTeleopMode{ui::TeleopMode::kScripted});
  }
}

// The teacher's time is the truth: a discarded take and a countdown count in the ledger, and the
// teleop the teacher chose is the one a reopened session starts with.
TEST_F(StudioControllerTest, EveryTakeCountsAndTheTeleopIsRemembered) {
  StudioOptions options = Options();
  options.countdown_s = 0.5;
  {
    StudioController controller(options);
    controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
    controller.Push(ui::StartRecording{});
    WaitFor(controller, [](const auto& now) {
      return now.recording && now.countdown_s <= 0 && now.recording_samples > 3;
    });
    controller.Push(ui::DiscardRecording{});
    const ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) {
      return !now.recording && now.teacher_discarded_takes > 0;
    });
    EXPECT_EQ(s.teacher_discarded_takes, 1);
    EXPECT_GT(s.teacher_discarded_seconds, 0.3);
    EXPECT_GT(s.teacher_countdown_seconds, 0.0);
    EXPECT_NEAR(s.teacher_seconds,
                s.teacher_demo_seconds + s.teacher_discarded_seconds + s.teacher_countdown_seconds +
                    s.teacher_play_seconds + s.teacher_placement_seconds,
                1e-6);
    EXPECT_TRUE(s.episodes.empty());
  }
  StudioController reopened(options);
  const ui::StudioSnapshot s =
      WaitFor(reopened, [](const auto& now) { return !now.session_dir.empty(); });
  EXPECT_EQ(s.teleop, ui::TeleopMode::kKeyboard);
  EXPECT_EQ(s.teacher_discarded_takes, 1);
}

// The simulated cell's beacon stands beside the plate: marking another object with it is
// refused by name (a real cell accepts any object: the beacon reports where it is stuck).
TEST_F(StudioControllerTest, TheSimulatedBeaconCannotMarkAnotherObject) {
  StudioController controller(Options());
  controller.Push(ui::AssignBeacon{"plate", "bowl"});
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors[0], HasSubstr("cannot mark the bowl"));
  EXPECT_EQ(s.session_dir.empty(), false);
  controller.Push(ui::DismissErrors{});
  controller.Push(ui::AssignBeacon{"plate", "plate"});
  s = WaitFor(controller, [](const auto& now) {
    return now.status.find("marks the plate") != std::string::npos;
  });
  EXPECT_TRUE(s.errors.empty());
}

// Demonstrations from two teleops are flagged (a policy learns best from one teacher's style),
// and marking the odd one Bad clears it.
TEST_F(StudioControllerTest, DemonstrationsFromTwoTeachersAreFlagged) {
  StudioController controller(Options());
  controller.Push(ui::StartRecording{});  // the scripted teacher
  ui::StudioSnapshot s = WaitFor(
      controller, [](const auto& now) { return !now.recording && now.episodes.size() == 1; });
  EXPECT_EQ(s.teacher_mix_warning, "");
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  controller.Push(ui::StartRecording{});
  WaitFor(controller, [](const auto& now) { return now.recording_samples > 3; });
  controller.Push(ui::StopRecording{});  // kept, not done
  s = WaitFor(controller,
              [](const auto& now) { return !now.recording && now.episodes.size() == 2; });
  ASSERT_EQ(s.episodes.size(), 2u);
  EXPECT_NE(s.teacher_mix_warning.find("2 teachers"), std::string::npos) << s.teacher_mix_warning;
  controller.Push(ui::MarkEpisodeBad{s.episodes[1].name, true});
  s = WaitFor(controller,
              [](const auto& now) { return now.episodes.size() == 2 && now.episodes[1].bad; });
  EXPECT_EQ(s.teacher_mix_warning, "");
}

// A gamepad (here a FIFO carrying the joystick API's events, as /dev/input/js0 would) is found,
// drives the arm with its left stick, grips with A, keeps the take with Start, and its
// unplugging stops the arm and is reported.
TEST_F(StudioControllerTest, AGamepadDrivesTheArmAndItsUnpluggingIsReported) {
  const std::string fifo = (dir_ / "js0").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const int writer = open(fifo.c_str(), O_RDWR);  // read-write: opening does not wait for a reader
  ASSERT_GE(writer, 0);
  const auto send = [&](uint8_t type, uint8_t number, int16_t value) {
    js_event e{0, value, type, number};
    ASSERT_EQ(write(writer, &e, sizeof(e)), static_cast<ssize_t>(sizeof(e)));
  };
  StudioOptions options = Options();
  options.gamepad_paths = {fifo};
  StudioController controller(options);
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) {
    for (const ui::TeleopChoice& c : now.teleop_choices) {
      if (c.mode == ui::TeleopMode::kGamepad) return c.available;
    }
    return false;
  });
  controller.Push(ui::OpenStep{teach::Step::kRecord});  // where the 3-D view is drawn
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kGamepad});
  controller.Push(ui::StartRecording{});
  s = WaitFor(controller,
              [](const auto& now) { return now.recording && now.teacher_view.available; });
  EXPECT_EQ(s.teleop, ui::TeleopMode::kGamepad);
  // The stick, like the arrows, moves the arm as the teacher's view shows it.
  const std::array<float, 2> start = s.teacher_view.spot_pixel;
  send(JS_EVENT_AXIS, 0, 32767);  // left stick right
  s = WaitFor(
      controller, [&](const auto& now) { return now.teacher_view.spot_pixel[0] > start[0] + 20; },
      20);
  EXPECT_NEAR(s.teacher_view.spot_pixel[1], start[1], 6);
  send(JS_EVENT_AXIS, 0, 0);
  send(JS_EVENT_BUTTON, 0, 1);  // A: grip
  s = WaitFor(
      controller, [](const auto& now) { return now.gripper_closed; }, 20);
  send(JS_EVENT_BUTTON, 7, 1);  // Start: keep
  s = WaitFor(controller, [](const auto& now) { return !now.recording && !now.episodes.empty(); });
  ASSERT_EQ(s.episodes.size(), 1u);
  close(writer);  // unplugged
  s = WaitFor(controller, [](const auto& now) {
    return !now.errors.empty() && now.errors.back().find("holds still") != std::string::npos;
  });
  EXPECT_THAT(s.errors.back(), HasSubstr("js0 closed"));
  bool listed = false;
  for (const ui::DeviceView& d : s.devices) {
    if (d.kind == "gamepad") {
      listed = true;
      EXPECT_FALSE(d.connected);
      EXPECT_THAT(d.last_error, HasSubstr("closed"));
    }
  }
  EXPECT_TRUE(listed);
}

// The e-stop ends a recording and sets the take aside for the teacher to keep or discard,
// refuses whatever would move the arm until it is released, and works with no session open;
// the envelope's count shows on the Cell screen.
TEST_F(StudioControllerTest, TheEStopEndsARecordingAndRefusesMotionUntilReleased) {
  StudioOptions options = Options();
  StudioController controller(options);
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  controller.Push(ui::StartRecording{});
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.recording; });
  EXPECT_EQ(s.safety.limits, "1 rad/s, 5 rad/s^2, tool floor 5 mm, watchdog 200 ms");
  controller.Push(ui::EmergencyStop{true, "test"});
  s = WaitFor(controller, [](const auto& now) { return now.safety.estop; });
  EXPECT_FALSE(s.recording);
  EXPECT_TRUE(s.episodes.empty());
  EXPECT_EQ(s.safety.estop_reason, "test");
  EXPECT_THAT(s.status, HasSubstr("set aside"));
  EXPECT_THAT(s.pending_take, HasSubstr("The e-stop stopped the take after"));
  // Nothing else starts until the teacher has decided.
  controller.Push(ui::StartRecording{});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors[0], HasSubstr("cannot record: keep or discard the last take first"));
  controller.Push(ui::DismissErrors{});
  controller.Push(ui::DiscardRecording{});
  s = WaitFor(controller, [](const auto& now) { return now.pending_take.empty(); });
  EXPECT_TRUE(s.episodes.empty());

  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kScripted});
  controller.Push(ui::StartRecording{});
  controller.Push(ui::RecordPlay{5});
  controller.Push(ui::RunRollouts{1});
  s = WaitFor(controller, [](const auto& now) { return now.errors.size() >= 3; });
  ASSERT_EQ(s.errors.size(), 3u);
  EXPECT_THAT(s.errors[0], HasSubstr("cannot record: the e-stop is engaged (test)"));
  EXPECT_THAT(s.errors[1], HasSubstr("cannot record play data: the e-stop is engaged"));
  EXPECT_THAT(s.errors[2], HasSubstr("cannot roll out: the e-stop is engaged"));
  EXPECT_FALSE(s.recording);
  EXPECT_FALSE(s.recording_play);

  controller.Push(ui::EmergencyStop{false, ""});
  controller.Push(ui::StartRecording{});
  s = WaitFor(controller, [](const auto& now) { return !now.episodes.empty() && !now.recording; });
  EXPECT_FALSE(s.safety.estop);
  ASSERT_EQ(s.episodes.size(), 1u);
  // Every command of the demonstration passed the envelope (the expert's are all inside it).
  EXPECT_GE(s.safety.commands, s.episodes[0].samples);
  EXPECT_EQ(s.safety.changed, 0);

  StudioController picker(Options(""));
  picker.Push(ui::EmergencyStop{true, "no session"});
  s = WaitFor(picker, [](const auto& now) { return now.safety.estop; });
  EXPECT_TRUE(s.errors.empty());
  // The arm of a session opened under the e-stop is held by its own latch from the start: the
  // safety panel shows the arm's guard (its limits), and the guard says it is stopped.
  picker.Push(ui::OpenSession{(dir_ / "held").string()});
  s = WaitFor(picker, [](const auto& now) { return !now.safety.limits.empty(); });
  EXPECT_TRUE(s.safety.estop);
  EXPECT_EQ(s.safety.estop_reason, "no session");
}

// A take the e-stop stopped is kept when the teacher says so, as a demonstration not done.
TEST_F(StudioControllerTest, ATakeSetAsideByTheEStopCanBeKeptAsNotDone) {
  StudioController controller(Options());
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  controller.Push(ui::StartRecording{});
  WaitFor(controller, [](const auto& now) { return now.recording_samples >= 3; });
  controller.Push(ui::EmergencyStop{true, "test"});
  ui::StudioSnapshot s =
      WaitFor(controller, [](const auto& now) { return !now.pending_take.empty(); });
  controller.Push(ui::StopRecording{});  // "Keep as not done"
  s = WaitFor(controller, [](const auto& now) { return !now.episodes.empty(); });
  ASSERT_EQ(s.episodes.size(), 1u);
  EXPECT_FALSE(s.episodes[0].succeeded);
  EXPECT_GE(s.episodes[0].samples, 3);
  EXPECT_TRUE(s.pending_take.empty());
}

// A person's take that runs into the time limit (20 s at the arm's 10 Hz) is not committed by
// itself: it waits for Keep or Discard, and Discard keeps nothing.
TEST_F(StudioControllerTest, AKeyboardTakeAtTheTimeLimitWaitsForTheTeacher) {
  StudioController controller(Options());
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  controller.Push(ui::StartRecording{});
  ui::StudioSnapshot s = WaitFor(
      controller, [](const auto& now) { return !now.pending_take.empty(); }, 120);
  EXPECT_THAT(s.pending_take, HasSubstr("reached its 20 s limit before the task was done"));
  // No key was pressed: it says what became of the toast and that the arm stood still.
  EXPECT_THAT(s.pending_take, HasSubstr("it never picked the toast up"));
  EXPECT_THAT(s.pending_take, HasSubstr("the arm stood still for 20.0 s"));
  EXPECT_FALSE(s.recording);
  EXPECT_TRUE(s.episodes.empty()) << "nothing is committed unasked";
  controller.Push(ui::DiscardRecording{});
  s = WaitFor(controller, [](const auto& now) { return now.pending_take.empty(); });
  EXPECT_TRUE(s.episodes.empty());
  // `recon session info` counts the discarded take among what the teacher spent.
  const store::Session session =
      store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
  const cli::SessionResults results = cli::ReadSessionResults(session);
  const std::string info =
      cli::SessionInfoText(session, cli::SessionInfoJson(session, results), results);
  EXPECT_THAT(info, HasSubstr("with 1 take discarded or recorded over (20.0 s)")) << info;
}

// Delete is undoable: the episode comes back from the trash with its mark.
TEST_F(StudioControllerTest, UndoBringsADeletedDemonstrationBack) {
  StudioController controller(Options());
  controller.Push(ui::StartRecording{});
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return !now.episodes.empty(); });
  const std::string name = s.episodes[0].name;
  const int samples = s.episodes[0].samples;
  controller.Push(ui::MarkEpisodeBad{name, true});
  controller.Push(ui::DeleteEpisode{name});
  s = WaitFor(controller, [](const auto& now) { return now.episodes.empty(); });
  EXPECT_EQ(s.undo_delete, name);
  controller.Push(ui::UndoDelete{});
  s = WaitFor(controller, [](const auto& now) { return !now.episodes.empty(); });
  ASSERT_EQ(s.episodes.size(), 1u);
  EXPECT_EQ(s.episodes[0].name, name);
  EXPECT_EQ(s.episodes[0].samples, samples);
  EXPECT_TRUE(s.episodes[0].bad);
  EXPECT_EQ(s.undo_delete, "");
  EXPECT_TRUE(s.errors.empty());
}

// A person's take starts after a countdown: the arm takes no step and nothing is recorded
// until it has run out, and then the take runs.
TEST_F(StudioControllerTest, AKeyboardTakeStartsAfterItsCountdown) {
  StudioOptions options = Options();
  options.countdown_s = 4;
  StudioController controller(options);
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kKeyboard});
  ui::TeleopInput right;
  right.screen_right = 1;
  controller.Push(ui::StartRecording{});
  controller.Push(right);  // keys held during the countdown move nothing yet
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.recording; });
  EXPECT_GT(s.countdown_s, 0.0);
  EXPECT_LE(s.countdown_s, 4.0);
  EXPECT_EQ(s.recording_samples, 0);
  s = WaitFor(
      controller, [](const auto& now) { return now.recording_samples > 0; }, 30);
  EXPECT_EQ(s.countdown_s, 0.0);
  controller.Push(ui::DiscardRecording{});
  s = WaitFor(controller, [](const auto& now) { return !now.recording; });
  EXPECT_TRUE(s.episodes.empty());
}

// "Open in browser" runs the desktop's opener on the report (here a script that notes what it
// was given); without a report, or with an opener that is not there, it says so.
TEST_F(StudioControllerTest, TheReportOpensWithTheDesktopsOpener) {
  const fs::path opened = dir_ / "opened.txt";
  const fs::path opener = dir_ / "opener.sh";
  std::ofstream(opener) << "#!/bin/sh\nprintf '%s' \"$1\" > " << opened.string() << ".tmp && mv "
                        << opened.string() << ".tmp " << opened.string() << "\n";
  fs::permissions(opener, fs::perms::owner_all);
  StudioOptions options = Options();
  options.open_command = opener.string();
  {
    StudioController controller(options);
    controller.Push(ui::OpenReport{});
    ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
    EXPECT_THAT(s.errors[0], HasSubstr("write the report first"));
    controller.Push(ui::DismissErrors{});
    controller.Push(ui::StartRecording{});
    WaitFor(controller, [](const auto& now) { return !now.episodes.empty(); });
    controller.Push(ui::WriteReport{});
    s = WaitFor(controller, [](const auto& now) { return !now.report_path.empty(); });
    controller.Push(ui::OpenReport{});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!fs::exists(opened) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::ifstream in(opened);
    const std::string given((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(given, (dir_ / "session" / "report" / "report.html").string());
    s = WaitFor(controller,
                [](const auto& now) { return now.status.find("Opened") != std::string::npos; });
    EXPECT_TRUE(s.errors.empty());
  }  // the session is free for the next studio

  {
    // An opener that starts and then fails (xdg-open exits 3 when it finds no browser) is an
    // error naming its exit, not "Opened".
    const fs::path failing = dir_ / "failing.sh";
    std::ofstream(failing) << "#!/bin/sh\nexit 3\n";
    fs::permissions(failing, fs::perms::owner_all);
    StudioOptions fails = Options();
    fails.open_command = failing.string();
    StudioController controller(fails);
    controller.Push(ui::OpenReport{});
    ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
    EXPECT_THAT(s.errors[0], HasSubstr("could not open the report (exit status 3"));
    EXPECT_THAT(s.errors[0], HasSubstr("report.html"));
    EXPECT_THAT(s.status, Not(HasSubstr("Opened")));
  }

  StudioOptions missing = Options();
  missing.open_command = (dir_ / "no-such-opener").string();
  StudioController other(missing);
  other.Push(ui::OpenReport{});
  ui::StudioSnapshot s = WaitFor(other, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors[0], HasSubstr("cannot open the report with"));
  EXPECT_THAT(s.errors[0], HasSubstr("report.html"));
}

// The Cell screen's list of what is plugged in follows the device folder: a port that appears is
// listed at the next scan (or at once on Rescan), with no session needed.
TEST_F(StudioControllerTest, TheCellScreenListsWhatIsPluggedIn) {
  const fs::path dev = dir_ / "dev";
  fs::create_directories(dev / "input");
  std::ofstream(dev / "ttyACM0").put('\n');
  std::ofstream(dev / "video0").put('\n');
  StudioOptions options = Options("");
  options.dev_dir = dev.string();
  options.device_scan_ms = 60000;  // only Rescan finds the new port within the test's time
  StudioController controller(options);
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.connected_scanned; });
  EXPECT_EQ(s.connected_where, dev.string());
  ASSERT_EQ(s.connected.size(), 2u);
  EXPECT_EQ(s.connected[0].kind, "beacon");
  EXPECT_EQ(s.connected[0].path, (dev / "ttyACM0").string());
  EXPECT_EQ(s.connected[1].kind, "camera");
  std::ofstream(dev / "ttyUSB3").put('\n');
  controller.Push(ui::RescanDevices{});
  s = WaitFor(
      controller, [](const auto& now) { return now.connected.size() == 3; }, 10);
  ASSERT_EQ(s.connected.size(), 3u);
  EXPECT_EQ(s.connected[1].path, (dev / "ttyUSB3").string());
}

// A scripted demonstration recorded in the studio is the one `recon record` records for the same
// scenario seed: the live view's beacon readings do not disturb the recording's noise.
TEST_F(StudioControllerTest, AStudioDemonstrationIsReproducibleFromItsSeed) {
  std::string session;
  {
    StudioOptions options = Options();
    options.beacon_noise_sigma = 0.05;  // noisy readings: each one draws from the generator
    StudioController controller(options);
    // Let the live view run (and read the beacon) for a while first.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    controller.Push(ui::StartRecording{});
    const ui::StudioSnapshot s = WaitFor(
        controller, [](const auto& now) { return !now.recording && !now.episodes.empty(); });
    session = s.session_dir;
  }
  const store::Session opened = store::Session::Open(session, store::Session::Access::kReadOnly);
  ASSERT_EQ(opened.demos().size(), 1u);
  const store::DemoRecord stored = opened.ReadDemo(opened.demos()[0].name);
  auto world = cli::MakeSessionWorld(opened.manifest(), opened.manifest().placement);
  teach::DemoRecorder recorder(*world, teach::ScriptedTeacher, "scripted-teleop");
  // demo_0 is the first take of configuration 0, with the session's injected noise.
  recorder.SetActionNoise(opened.manifest().demo_noise_sigma);
  teach::StartSessionDemo(recorder, *world, opened.manifest().seed, 0);
  EXPECT_EQ(opened.demos()[0].meta.seed, stored.meta.seed);
  while (recorder.Tick()) {
  }
  const store::DemoRecord fresh = recorder.Take();
  ASSERT_EQ(fresh.episode.samples.size(), stored.episode.samples.size());
  for (size_t i = 0; i < fresh.episode.samples.size(); ++i) {
    ASSERT_EQ(fresh.episode.samples[i].b, stored.episode.samples[i].b) << "sample " << i;
    ASSERT_EQ(fresh.episode.samples[i].u, stored.episode.samples[i].u) << "sample " << i;
  }
}

// Play data is recorded sample by sample with the latest sample shown, committed in chunks of
// one scenario each; stopping keeps what was recorded.
TEST_F(StudioControllerTest, PlayDataIsShownSampleBySampleAndCanBeStopped) {
  StudioOptions options = Options();
  options.real_time = true;  // 10 samples a second, so there is time to stop it
  StudioController controller(options);
  controller.Push(ui::RecordPlay{30});
  ui::StudioSnapshot s =
      WaitFor(controller, [](const auto& now) { return now.play_recorded >= 13; });
  EXPECT_TRUE(s.recording_play);
  EXPECT_EQ(s.play_target, 30);
  EXPECT_EQ(s.play_image.width, 64);
  EXPECT_EQ(s.play_reading.size(), 2u);
  EXPECT_EQ(s.play_samples, 10) << "the first chunk (one scenario's 10 samples) is committed";
  controller.Push(ui::StopPlay{});
  s = WaitFor(controller, [](const auto& now) { return !now.recording_play; });
  EXPECT_GE(s.play_samples, 13);
  EXPECT_LT(s.play_samples, 30);
  EXPECT_EQ(s.play_samples, s.play_recorded);
}

// The studio starts without a session at the picker, creates one, switches to another and back,
// and remembers them most recent first; a broken list is moved aside and reported.
TEST_F(StudioControllerTest, SessionsOpenFromThePickerAndAreRemembered) {
  fs::create_directories(dir_ / "config");
  { std::ofstream(dir_ / "config" / "recent.json") << "{\"sessions\": [3]}"; }
  StudioController controller(Options(""));
  ui::StudioSnapshot s = controller.Snapshot();
  EXPECT_FALSE(s.session_open);
  EXPECT_TRUE(s.picking_session);
  // Every step says what it waits for.
  ASSERT_EQ(s.steps.size(), static_cast<size_t>(teach::kNumSteps));
  EXPECT_THAT(s.steps[1].why_blocked, HasSubstr("session"));
  ASSERT_EQ(s.errors.size(), 1u);
  EXPECT_THAT(s.errors[0], HasSubstr("recent.json is unreadable"));
  EXPECT_TRUE(fs::exists(dir_ / "config" / "recent.json.corrupt"));

  controller.Push(ui::StartRecording{});  // nothing is open yet
  controller.Push(ui::OpenSession{(dir_ / "first").string()});
  s = WaitFor(controller, [](const auto& now) { return now.session_open; });
  EXPECT_THAT(s.errors.back(), HasSubstr("open or create a session first"));
  EXPECT_FALSE(s.picking_session);
  controller.Push(ui::OpenSession{(dir_ / "second").string()});
  s = WaitFor(controller,
              [&](const auto& now) { return now.session_dir.find("second") != std::string::npos; });
  controller.Push(ui::OpenSession{(dir_ / "first").string()});
  s = WaitFor(controller,
              [&](const auto& now) { return now.session_dir.find("first") != std::string::npos; });
  ASSERT_EQ(s.recent_sessions.size(), 2u);
  EXPECT_THAT(s.recent_sessions[0], HasSubstr("first"));
  EXPECT_THAT(s.recent_sessions[1], HasSubstr("second"));
  // A session of a world the studio does not teach is refused and the open one stays open.
  store::SessionManifest dynamic;
  {
    auto world = worlds::MakeWorld("dynamic2d", "none", 0.0, false, {});
    teach::SessionSetup setup;
    setup.world_name = "dynamic2d";
    setup.placement = "none";
    store::Session::Create((dir_ / "dynamic").string(), teach::NewSessionManifest(setup, *world));
  }
  controller.Push(ui::OpenSession{(dir_ / "dynamic").string()});
  s = WaitFor(controller, [](const auto& now) { return now.errors.size() >= 3; });
  EXPECT_THAT(s.errors.back(), HasSubstr("the studio teaches in the tabletop cell"));
  EXPECT_THAT(s.session_dir, HasSubstr("first"));
  // The list survives a restart.
  std::ifstream in(dir_ / "config" / "recent.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("first"));
}

// The Cell screen's rates are measured from what arrives, not written in.
TEST_F(StudioControllerTest, DeviceRatesAndBeaconHealthAreMeasured) {
  StudioOptions options = Options();
  options.beacon_noise_sigma = 0.05;  // the simulated DWM1001's, per axis
  StudioController controller(options);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const ui::StudioSnapshot s = controller.Snapshot();
  double camera = -1, beacons = -1;
  for (const ui::DeviceView& d : s.devices) {
    if (d.role == "camera") camera = d.rate_hz;
    if (d.role == "beacons") beacons = d.rate_hz;
  }
  EXPECT_GT(camera, 10.0);
  EXPECT_LT(camera, 40.0);
  EXPECT_GT(beacons, 7.0);
  EXPECT_LT(beacons, 12.0);
  ASSERT_EQ(s.beacons.size(), 1u);
  EXPECT_NEAR(s.beacons[0].rate_hz, beacons, 1e-9);
  // The readings' spread per axis, measured over the 10-15 readings so far: near the simulated
  // DWM1001's 5 cm (with 20+ samples over both axes, outside 2.5-8 cm has odds below 1e-4).
  EXPECT_GT(s.beacons[0].noise_m, 0.025);
  EXPECT_LT(s.beacons[0].noise_m, 0.08);
  EXPECT_LT(s.beacons[0].dropout_fraction, 0.2);
}

}  // namespace
}  // namespace recon::studio
