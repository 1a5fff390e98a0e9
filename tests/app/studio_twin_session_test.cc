// A whole teaching session on a real cell's path, through the studio's screens, headless: the
// studio (controller, screens, a headless window) opens a digital twin's profile (the scene drawn
// where a FakeUrController on loopback says the arm is, the plate's beacon a FakeDwm1001 on a
// pseudo-terminal), and the test clicks and types as a teacher: assigns the beacon, calibrates
// place by place, teaches two demonstrations with the keyboard, trains, runs two trials on the
// arm and judges them, and writes the report.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <imgui.h>
#include <stdlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "engine/report/image_png.h"
#include "engine/store/real_trials.h"
#include "engine/store/session.h"
#include "tests/app/headless_studio.h"
#include "tests/app/twin_rig.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Draws frames until the controller's snapshot satisfies `done` (the screen follows it).
ui::StudioSnapshot Until(HeadlessStudio& studio,
                         const std::function<bool(const ui::StudioSnapshot&)>& done,
                         const char* what, double timeout_s = 60) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    studio.driver().WaitFrames(1);
    ui::StudioSnapshot s = studio.controller().Snapshot();
    if (done(s)) return s;
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "timed out waiting for " << what << "; status: " << s.status
                    << (s.errors.empty() ? "" : "; last error: " + s.errors.back());
      return s;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

TEST(StudioTwinSessionTest, ATeacherRunsAWholeRealCellSessionThroughTheScreens) {
  char pattern[] = "/tmp/recon-studio-twin-session-XXXXXX";
  ASSERT_NE(::mkdtemp(pattern), nullptr);
  const fs::path dir = pattern;
  testing::TwinRig rig(dir / "twin");
  StudioOptions options;
  options.session_dir = (dir / "session").string();
  options.recent_sessions_file = (dir / "recent.json").string();
  options.cell_profile = rig.profile;
  options.dev_dir = (dir / "no-dev").string();
  options.calibration_points = 4;
  options.countdown_s = 0;
  options.train_steps = 20;
  options.rollout_tests = 2;
  {
    HeadlessStudio studio(options);
    ui::UiDriver& driver = studio.driver();
    // RECON_DOCS_IMAGES=DIR keeps the screens docs/hardware.md shows.
    const char* images = std::getenv("RECON_DOCS_IMAGES");
    const auto keep_screen = [&](const std::string& name) {
      if (images != nullptr)
        report::WritePng(driver.Screenshot(), (fs::path(images) / name).string());
    };
    Until(
        studio, [](const auto& s) { return s.camera_frame > 0; }, "the twin's first frame");

    // Beacons: the plate's beacon marks the plate (a real cell's objects are chosen from a list).
    driver.RunScript(R"(click Beacons##step
click marks##object-plate
click plate##for-plate
click Calibrate##step
click Collect points and fit)",
                     "beacons and calibration");
    // Calibrate: the teacher puts the beacon at each place the screen asks for.
    const std::vector<Eigen::Vector2d> places = {
        {0.35, -0.3}, {0.75, -0.25}, {0.7, 0.2}, {0.4, 0.15}};
    for (size_t i = 0; i < places.size(); ++i) {
      rig.PutPlate(places[i].x(), places[i].y());
      if (i == 2) {
        Until(
            studio,
            [](const auto& now) {
              return now.calibration.guided && now.calibration.guided->held_fraction > 0.3f;
            },
            "the hold at the third place");
        keep_screen("real_calibrate.png");
      }
      Until(
          studio,
          [&](const auto& s) {
            return s.calibration.points_collected >= static_cast<int>(i + 1) ||
                   !s.calibration.running;
          },
          "a calibration place");
    }
    ui::StudioSnapshot s = Until(
        studio, [](const auto& now) { return !now.calibration.running; }, "the fit");
    ASSERT_TRUE(s.calibration.present);
    EXPECT_TRUE(s.calibration.passed);
    EXPECT_EQ(s.calibration.residual_m.size(), 4u);

    // Record: two keyboard takes, the up arrow held for a second each.
    rig.PutPlate(0.55, 0.35);
    driver.RunScript("click Record##step", "record");
    for (int take = 1; take <= 2; ++take) {
      driver.Click("Start recording");
      // The second take waits for the arm to return home from where the first left it.
      Until(
          studio, [](const auto& now) { return now.recording && !now.take_homing; }, "the take");
      driver.Hold(ImGuiKey_UpArrow, 1.0);
      driver.Click("Stop and keep##take");
      s = Until(
          studio,
          [&](const auto& now) {
            return !now.recording && now.episodes.size() == static_cast<size_t>(take);
          },
          "the take's commit");
    }
    EXPECT_GE(s.episodes[0].samples, 5);
    // The teacher waited for the arm's way home before the second take (no countdown here):
    // the ledger counts that wait as the teacher's time.
    EXPECT_GT(s.teacher_countdown_seconds, 0.0);

    // Train both methods.
    driver.RunScript("click Train##step\nclick Train Baseline and RECON", "train");
    s = Until(
        studio,
        [](const auto& now) {
          return !now.training_running && now.training.size() == 2 && now.training[0].done &&
                 now.training[1].done;
        },
        "training", 180);
    // The step list is re-read from the session a moment after the job ends: wait for the
    // Rollouts step to open, as a person would see it enabled before clicking it.
    Until(
        studio,
        [](const auto& now) {
          for (const teach::StepStatus& step : now.steps) {
            if (step.step == teach::Step::kRollouts)
              return step.state != teach::StepState::kBlocked;
          }
          return false;
        },
        "the Rollouts step");

    // Rollouts: two trials of the Baseline on the arm, set up as shown and judged.
    driver.RunScript("click Rollouts##step\nclick Run 2 trials of Baseline", "trials");
    for (int trial = 1; trial <= 2; ++trial) {
      s = Until(
          studio,
          [&](const auto& now) {
            return now.trial.phase == ui::TrialPhase::kSetUp && now.trial.number == trial;
          },
          "the trial's layout");
      rig.SetUpLayout(s.trial);
      if (trial == 1) {
        // Once the twin's camera has drawn the layout set up (a few frames on).
        const uint64_t frame = studio.controller().Snapshot().camera_frame;
        Until(
            studio, [&](const auto& now) { return now.camera_frame >= frame + 4; },
            "the camera's next frames");
        keep_screen("real_trial.png");
      }
      const int64_t commands = rig.robot->commands_received();
      driver.Click("Ready: run trial " + std::to_string(trial));
      Until(
          studio, [](const auto& now) { return now.trial.step >= 5; }, "the policy's steps");
      driver.Click("STOP the trial");
      Until(
          studio, [](const auto& now) { return now.trial.phase == ui::TrialPhase::kJudge; },
          "the verdict");
      EXPECT_GT(rig.robot->commands_received(), commands + 5) << "the arm was not driven";
      driver.Click(trial == 1 ? "Success" : "Failure: missed the toast");
    }
    s = Until(
        studio, [](const auto& now) { return now.trial.phase == ui::TrialPhase::kNone; },
        "the trials' end");
    ASSERT_EQ(s.real_trials.size(), 1u);
    EXPECT_EQ(s.real_trials[0].successes, 1);
    EXPECT_EQ(s.real_trials[0].trials.size(), 2u);

    // The report.
    driver.RunScript("click Report##step\nclick Write the report", "report");
    s = Until(
        studio, [](const auto& now) { return !now.report_path.empty(); }, "the report");
    std::ifstream report(s.report_path);
    const std::string html((std::istreambuf_iterator<char>(report)),
                           std::istreambuf_iterator<char>());
    EXPECT_THAT(html, HasSubstr("Trials on the real arm"));
    EXPECT_THAT(html, HasSubstr("missed the toast"));
    EXPECT_THAT(html, HasSubstr("PASS"));
  }
  const store::Session session =
      store::Session::Open((dir / "session").string(), store::Session::Access::kReadOnly);
  EXPECT_EQ(session.manifest().cell, "real");
  EXPECT_EQ(session.demos().size(), 2u);
  EXPECT_EQ(session.demos()[0].meta.source, "keyboard-teleop");
  const std::optional<store::RealTrialLog> log = store::ReadRealTrialLog(session, "baseline");
  ASSERT_TRUE(log.has_value());
  EXPECT_EQ(log->trials.size(), 2u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon::studio
