// Every screen fits: each workflow step in its main states, drawn headless at the window sizes
// the studio supports (1024 x 640 up to 2560 x 1440), with nothing out of reach and nothing on
// top of anything else (ui/testing/layout_check.h says what counts as a fault).

#include <gtest/gtest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include <string>
#include <utility>
#include <vector>

#include "tests/ui/probe_test_support.h"
#include "tests/ui/studio_harness.h"
#include "tests/ui/studio_test_support.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/layout_check.h"
#include "ui/widgets/widget_registry.h"

namespace recon::ui {
namespace {

using testing::Probed;
using testing::Progress;
using testing::SnapshotAt;

struct WindowSize {
  int width, height;
  float ui_scale;
};

// From the smallest window the studio allows to a large desktop, and a high-DPI one drawn at
// scale 2 (the desktop's DPI setting).
const WindowSize kSizes[] = {{1024, 640, 1.0f},
                             {1280, 800, 1.0f},
                             {1920, 1080, 1.0f},
                             {2560, 1440, 1.0f},
                             {2560, 1440, 2.0f}};

std::string SizeName(const WindowSize& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height) +
         (size.ui_scale != 1.0f ? " at scale 2" : "");
}

/// The Record screen while a person's take runs, in its last seconds (the warning line shown).
StudioSnapshot KeyboardTakeRunning() {
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  s.teleop = TeleopMode::kKeyboard;
  s.recording = true;
  s.busy_with = "the recording";
  s.recording_samples = 170;
  s.recording_max_samples = 200;
  s.grip_m[2] = 0.009f;
  s.grip.state = GripState::kHolding;
  s.gripper_closed = true;
  s.teacher_discarded_takes = 11;
  s.teacher_discarded_seconds = 612.4;
  s.teacher_countdown_seconds = 45.0;
  return s;
}

/// Every step in its main states, named for the failure messages.
std::vector<std::pair<std::string, StudioSnapshot>> MainStates() {
  std::vector<std::pair<std::string, StudioSnapshot>> states;
  const auto add = [&](const std::string& name, const StudioSnapshot& s) {
    states.emplace_back(name, s);
  };
  add("session picker", SnapshotAt(Progress::kNothing, teach::Step::kCell));
  add("cell", SnapshotAt(Progress::kCellUp, teach::Step::kCell));
  add("beacons", SnapshotAt(Progress::kCellUp, teach::Step::kBeacons));
  add("beacons assigned", SnapshotAt(Progress::kBeaconAssigned, teach::Step::kBeacons));
  add("calibrate", SnapshotAt(Progress::kBeaconAssigned, teach::Step::kCalibrate));
  add("calibrated", SnapshotAt(Progress::kCalibrated, teach::Step::kCalibrate));
  add("record, empty", SnapshotAt(Progress::kCalibrated, teach::Step::kRecord));
  add("record, recorded", SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  add("record, a keyboard take running", KeyboardTakeRunning());
  StudioSnapshot gamepad = KeyboardTakeRunning();
  gamepad.teleop = TeleopMode::kGamepad;
  add("record, a gamepad take running", gamepad);
  // The readout's longest lines: the wrist at its limit, for each device.
  for (const TeleopMode mode : {TeleopMode::kKeyboard, TeleopMode::kGamepad}) {
    StudioSnapshot limit = KeyboardTakeRunning();
    limit.teleop = mode;
    limit.grip.wrist_limit_deg = 90;
    limit.grip.wrist_turn_deg = -90;
    add(std::string("record, the wrist at its limit (") + TeleopModeLabel(mode) + ")", limit);
  }
  StudioSnapshot pending = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  pending.teleop = TeleopMode::kKeyboard;
  pending.pending_take = "The take reached its 20 s limit before the task was done";
  pending.undo_delete = "demo_2";
  add("record, a take waiting to be kept", pending);
  StudioSnapshot many = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  for (int i = 4; i < 16; ++i) {
    many.episodes.push_back({"demo_" + std::to_string(i), 180, 18.0, true, false, "train", ""});
  }
  add("record, 16 demonstrations", many);
  StudioSnapshot watching = SnapshotAt(Progress::kTrained, teach::Step::kRecord);
  watching.episode_playback.episode = "demo_1";
  watching.episode_playback.frames = 130;
  watching.episode_playback.frame = 12;
  watching.episode_playback.methods = {{"baseline", "Baseline"}, {"recon", "RECON (Play)"}};
  watching.episode_playback.method = "recon";
  watching.episode_playback.image = testing::SyntheticCamera();
  watching.episode_playback.image_frame = 1;
  watching.saliency = SaliencyMode::kGradient;
  add("record, a demonstration played back", watching);
  add("play", SnapshotAt(Progress::kRecorded, teach::Step::kPlay));
  StudioSnapshot playing = SnapshotAt(Progress::kRecorded, teach::Step::kPlay);
  playing.recording_play = true;
  playing.play_recorded = 12;
  playing.play_target = 30;
  playing.play_image = testing::SyntheticCamera();
  playing.play_image_frame = 1;
  playing.play_reading = {0.609f, 0.468f};
  add("play, recording", playing);
  add("train, untrained", SnapshotAt(Progress::kRecorded, teach::Step::kTrain));
  StudioSnapshot training = SnapshotAt(Progress::kTrained, teach::Step::kTrain);
  training.training_running = true;
  training.busy_with = "the training";
  for (TrainingView& t : training.training) t.done = false;
  add("train, training", training);
  add("train, trained", SnapshotAt(Progress::kTrained, teach::Step::kTrain));
  add("rollouts, none yet", SnapshotAt(Progress::kTrained, teach::Step::kRollouts));
  StudioSnapshot rolling = SnapshotAt(Progress::kTrained, teach::Step::kRollouts);
  rolling.rollouts_running = true;
  rolling.rollout_steps_done = 120;
  rolling.rollout_steps_total = 400;
  rolling.busy_with = "the rollouts";
  add("rollouts, running", rolling);
  StudioSnapshot done = SnapshotAt(Progress::kDone, teach::Step::kRollouts);
  done.rollout_limit_s = 29.6;
  done.longest_take_s = 19.7;
  add("rollouts, done", done);
  StudioSnapshot probed = Probed();
  for (RolloutView& r : probed.rollouts) r.has_replay = true;  // the playback above the check
  add("rollouts, what it looks at", probed);
  add("report, nothing written", SnapshotAt(Progress::kTrained, teach::Step::kReport));
  add("report, written", SnapshotAt(Progress::kDone, teach::Step::kReport));
  StudioSnapshot stopped = SnapshotAt(Progress::kRecorded, teach::Step::kRecord);
  stopped.safety.estop = true;
  stopped.safety.estop_reason = "e-stop button";
  add("record, e-stop engaged", stopped);
  return states;
}

class EveryScreenFitsTest : public ::testing::TestWithParam<WindowSize> {};

TEST_P(EveryScreenFitsTest, NothingIsOutOfReachOrUnderAnotherWidget) {
  const WindowSize size = GetParam();
  StudioHarness harness(size.width, size.height, size.ui_scale);
  for (const auto& [name, snapshot] : MainStates()) {
    harness.Show(snapshot);
    const WidgetRegistry& registry = WidgetRegistry::ForThisThread();
    EXPECT_GE(registry.Placements().size(), 3u) << name;  // the check looked at something
    for (const std::string& fault : LayoutFaults(registry)) {
      ADD_FAILURE() << SizeName(size) << ", " << name << ": " << fault;
    }
    // What lies below the fold (or beside it) is reachable: scrolling brings it into view.
    std::vector<std::string> out_of_view;
    for (const WidgetPlacement& p : registry.Placements()) {
      const bool seen =
          p.rect.min_x >= p.panel_view.min_x - 1 && p.rect.max_x <= p.panel_view.max_x + 1 &&
          p.rect.min_y >= p.panel_view.min_y - 1 && p.rect.max_y <= p.panel_view.max_y + 1;
      if (!seen && !p.region) out_of_view.push_back(p.label);
    }
    for (const std::string& label : out_of_view) {
      EXPECT_NO_THROW(harness.driver().ScrollIntoView(label))
          << SizeName(size) << ", " << name << ": " << label;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Sizes, EveryScreenFitsTest, ::testing::ValuesIn(kSizes),
                         [](const ::testing::TestParamInfo<WindowSize>& param) {
                           return std::to_string(param.param.width) + "x" +
                                  std::to_string(param.param.height) + "_scale" +
                                  std::to_string(static_cast<int>(param.param.ui_scale));
                         });

float WidthOf(StudioHarness& harness, const std::string& label) {
  const std::optional<WidgetRect> r = WidgetRegistry::ForThisThread().Find(label);
  EXPECT_TRUE(r.has_value()) << label;
  return r ? r->max_x - r->min_x : 0;
}

// The teacher's 3-D view and the live camera views take the room a larger window gives them.
TEST(ViewsGrowTest, TheLiveViewsGrowWithTheWindow) {
  const struct {
    teach::Step step;
    Progress progress;
    const char* view;
  } views[] = {{teach::Step::kRecord, Progress::kRecorded, "teacher-view"},
               {teach::Step::kCell, Progress::kCellUp, "camera##cell"},
               {teach::Step::kBeacons, Progress::kCellUp, "camera##beacons"},
               {teach::Step::kPlay, Progress::kRecorded, "camera##play"}};
  for (const auto& v : views) {
    StudioHarness small(1280, 800);
    small.Show(SnapshotAt(v.progress, v.step));
    const float at_1280 = WidthOf(small, v.view);
    StudioHarness large(1920, 1080);
    large.Show(SnapshotAt(v.progress, v.step));
    const float at_1920 = WidthOf(large, v.view);
    EXPECT_GT(at_1920, 1.25f * at_1280) << v.view << ": " << at_1280 << " -> " << at_1920;
  }
}

// "Check what it looks at" runs under the rollouts, below the fold of a small window: its
// results, once they arrive, are scrolled into view.
TEST(ScrollingTest, TheProbesResultsComeIntoViewWhenTheyArrive) {
  StudioHarness harness(1024, 640);
  StudioSnapshot running = Probed();
  running.probe = {};
  running.probe.running = true;
  running.probe.phase = "moving objects";
  running.probe.total = 300;
  running.busy_with = "the check";
  harness.Show(running);
  harness.Show(Probed());
  const std::optional<WidgetPlacement> results =
      WidgetRegistry::ForThisThread().FindPlacement("probe-results");
  ASSERT_TRUE(results.has_value());
  EXPECT_GE(results->rect.min_y, results->panel_view.min_y - 1);
  EXPECT_LE(results->rect.min_y, results->panel_view.max_y - 100)
      << "the results' table starts below the fold";
}

// A window smaller than the smallest layout (a headless --width, a window manager that ignores
// the limit) says so, and its step list and screen scroll to what does not fit: the screen
// keeps the smallest layout, so no panel inside it is cut or overlaps another.
TEST(ScrollingTest, AWindowBelowTheMinimumSaysSoAndItsPanelsScroll) {
  StudioHarness harness(800, 500);
  for (const auto& [name, snapshot] : MainStates()) {
    if (snapshot.safety.estop) continue;  // the e-stop's line takes the status bar's place
    harness.Show(snapshot);
    EXPECT_TRUE(harness.driver().Drawn("window-too-small")) << name;
    for (const std::string& fault : LayoutFaults(WidgetRegistry::ForThisThread())) {
      ADD_FAILURE() << "800x500, " << name << ": " << fault;
    }
  }
  StudioHarness fits(kMinWindowWidth, kMinWindowHeight);
  fits.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  EXPECT_FALSE(fits.driver().Drawn("window-too-small"));
}

}  // namespace
}  // namespace recon::ui
