// The studio's trials on a real cell's path without hardware: a digital twin (cell::TwinCamera
// drawing the tabletop scene with the UR5 where a FakeUrController on loopback TCP says it is),
// the plate's beacon a FakeDwm1001 on a pseudo-terminal reporting through a hidden UWB frame. The
// arm returns home before each trial, the policy drives it, the person judges, and every judged
// trial is kept through faults (studio_twin_calibration_test.cc has the Calibrate step).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "app/cli/result_staleness.h"
#include "app/cli/session_summary.h"
#include "app/studio/studio_controller.h"
#include "engine/calib/calibration.h"
#include "engine/store/real_trials.h"
#include "engine/store/session.h"
#include "engine/worlds/ur5_arm.h"
#include "tests/app/studio_twin_fixture.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using testing::StudioTwinCellTest;
using testing::WaitFor;

TEST_F(StudioTwinCellTest, RunsTrialsOnTheRealArmJudgedByThePersonKeepingEveryJudgedOne) {
  calib::SaveCalibration(testing::TwinCalibration(), (dir_ / "cal.json").string());
  StudioOptions options = Options();
  options.calibration_file = (dir_ / "cal.json").string();
  options.train_steps = 20;
  StudioController controller(options);
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.camera_frame > 0; });
  controller.Push(ui::AssignBeacon{"plate", "plate"});
  // Two keyboard demonstrations: the arm moves up the screen, then is kept. The second starts
  // where the first left the arm: it returns home first, so both begin where the trials will.
  for (int take = 0; take < 2; ++take) {
    controller.Push(ui::StartRecording{});
    s = WaitFor(controller, [](const auto& now) { return now.recording; });
    if (take == 1) {
      s = WaitFor(controller, [](const auto& now) { return now.take_homing; });
      EXPECT_EQ(s.recording_samples, 0);
    }
    ui::TeleopInput up;
    up.screen_up = 1;
    controller.Push(up);
    s = WaitFor(controller, [](const auto& now) { return now.recording_samples >= 8; });
    controller.Push(ui::TeleopInput{});
    controller.Push(ui::StopRecording{});
    s = WaitFor(controller, [&](const auto& now) {
      return !now.recording && now.episodes.size() == static_cast<size_t>(take + 1);
    });
  }
  {
    const store::Session session =
        store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
    const Dataset data = session.LoadDataset();
    ASSERT_EQ(data.demos.size(), 2u);
    for (const Episode& demo : data.demos) {
      // x is the joints minus home: each take's first sample is at home.
      for (int j = 0; j < 6; ++j)
        EXPECT_LT(std::abs(demo.samples[0].x[static_cast<size_t>(j)]), 0.01);
    }
  }
  // Trials need a trained model.
  controller.Push(ui::StartTrials{"baseline", 2});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors.back(), HasSubstr("train baseline first"));
  controller.Push(ui::DismissErrors{});
  controller.Push(ui::StartTraining{{"baseline"}, 0});
  s = WaitFor(
      controller,
      [](const auto& now) {
        return !now.training_running && !now.training.empty() && now.training[0].done;
      },
      120);

  controller.Push(ui::StartTrials{"baseline", 2});
  s = WaitFor(controller,
              [](const auto& now) { return now.trial.phase == ui::TrialPhase::kSetUp; });
  EXPECT_EQ(s.trial.number, 1);
  EXPECT_EQ(s.trial.last, 2);
  EXPECT_EQ(s.busy_with, "the trials");
  // The layout to set up: the test plan's first scene, each object where the camera sees it.
  ASSERT_EQ(s.trial.layout.size(), 3u);
  const tags::PinholeCamera camera = rig_->scene.TopCamera(1280, 960);
  for (const ui::TrialView::Object& o : s.trial.layout) {
    ASSERT_TRUE(o.pixel.has_value()) << o.name;
    const Eigen::Vector2d expected = camera.Project({o.table_m[0], o.table_m[1], 0.0});
    EXPECT_NEAR((*o.pixel)[0], expected.x(), 3.0) << o.name;
    EXPECT_NEAR((*o.pixel)[1], expected.y(), 3.0) << o.name;
  }
  // Trial 1: set up, run, stopped by the person after a few steps, judged a success. The arm
  // was left away from home (a take ends wherever the teacher stopped): it returns home first,
  // so the policy starts where every demonstration began.
  rig_->SetUpLayout(s.trial);
  std::array<double, 6> away = worlds::Ur5Arm::kHome;
  away[0] += 0.25;
  away[2] -= 0.15;
  rig_->robot->Teleport(away);
  const int64_t commands = rig_->robot->commands_received();
  controller.Push(ui::RunTrial{});
  s = WaitFor(controller,
              [](const auto& now) { return now.trial.phase == ui::TrialPhase::kHoming; });
  EXPECT_THAT(s.status, HasSubstr("returns to its home pose"));
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kRunning && now.trial.step >= 5;
  });
  controller.Push(ui::StopTrial{});
  s = WaitFor(controller,
              [](const auto& now) { return now.trial.phase == ui::TrialPhase::kJudge; });
  EXPECT_TRUE(s.trial.stopped);
  const int trial_one_steps = s.trial.step;
  EXPECT_GT(rig_->robot->commands_received(), commands + 5);  // the policy drove the real path
  controller.Push(ui::JudgeTrial{true, ""});
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kSetUp && now.trial.number == 2;
  });
  ASSERT_EQ(s.real_trials.size(), 1u);
  EXPECT_EQ(s.real_trials[0].successes, 1);

  // Trial 2: the e-stop mid-trial stops it, unjudged and not kept; run again, judged a failure.
  rig_->SetUpLayout(s.trial);
  controller.Push(ui::RunTrial{});
  s = WaitFor(controller, [](const auto& now) { return now.trial.step >= 3; });
  controller.Push(ui::EmergencyStop{true, "test"});
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kSetUp && !now.trial.message.empty();
  });
  EXPECT_THAT(s.trial.message, HasSubstr("the e-stop (test)"));
  EXPECT_THAT(s.trial.message, HasSubstr("not kept"));
  EXPECT_EQ(s.trial.number, 2);
  controller.Push(ui::RunTrial{});  // refused while the e-stop holds
  s = WaitFor(controller, [](const auto& now) {
    return !now.errors.empty() && now.errors.back().find("e-stop is engaged") != std::string::npos;
  });
  controller.Push(ui::EmergencyStop{false, ""});
  controller.Push(ui::RunTrial{});
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kRunning && now.trial.step >= 3;
  });
  controller.Push(ui::StopTrial{});
  s = WaitFor(controller,
              [](const auto& now) { return now.trial.phase == ui::TrialPhase::kJudge; });
  controller.Push(ui::JudgeTrial{false, "missed the toast"});
  s = WaitFor(controller, [](const auto& now) { return now.trial.phase == ui::TrialPhase::kNone; });
  EXPECT_THAT(s.status, HasSubstr("Trials done"));

  // In the session: both judged trials with their verdicts and the frames the policy saw.
  const store::Session session =
      store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
  const std::optional<store::RealTrialLog> log = store::ReadRealTrialLog(session, "baseline");
  ASSERT_TRUE(log.has_value());
  ASSERT_EQ(log->trials.size(), 2u);
  EXPECT_TRUE(log->trials[0].succeeded);
  EXPECT_TRUE(log->trials[0].stopped);
  EXPECT_EQ(log->trials[0].steps, trial_one_steps);
  EXPECT_FALSE(log->trials[1].succeeded);
  EXPECT_EQ(log->trials[1].reason, "missed the toast");
  EXPECT_THAT(log->cell, ::testing::StartsWith("real (camera: "));  // the cell and its devices
  EXPECT_THAT(log->cell, HasSubstr("arm: "));
  // `recon session info` says so too.
  const cli::SessionResults results = cli::ReadSessionResults(session);
  const nlohmann::json info = cli::SessionInfoJson(session, results);
  EXPECT_EQ(info["real_trials"]["baseline"]["successes"], 1);
  EXPECT_TRUE(info["real_trials"]["baseline"]["out_of_date"].is_null());
  EXPECT_THAT(cli::SessionInfoText(session, info, results),
              HasSubstr("real trials:    baseline: 1 of 2 succeeded on the real arm"));
  ASSERT_TRUE(log->trials[0].frames.has_value());
  const store::TrialFrames frames =
      store::ReadTrialFrames((fs::path(session.dir()) / *log->trials[0].frames).string());
  EXPECT_EQ(static_cast<int>(frames.y.size()), trial_one_steps);
  // The policy's first observation: the joints at home (x is the joints minus home).
  for (int j = 0; j < 6; ++j) EXPECT_LT(std::abs(frames.x[0][static_cast<size_t>(j)]), 0.01) << j;
  EXPECT_EQ(frames.y[0].size(), 3u * 64 * 64);
  EXPECT_EQ(frames.u[0].size(), 7u);
  controller.Push(ui::ShowTrialFrame{"baseline", 1, 2});
  s = WaitFor(controller, [](const auto& now) { return now.trial_playback.frame == 2; });
  EXPECT_EQ(s.trial_playback.frames, trial_one_steps);
  EXPECT_EQ(s.trial_playback.image.width, 64);
  // What drives the action, laid over the frames the real arm's camera recorded.
  const RgbImage recorded = s.trial_playback.image;
  controller.Push(ui::SetSaliency{ui::SaliencyMode::kGradient});
  s = WaitFor(controller,
              [&](const auto& now) { return now.trial_playback.image.rgb != recorded.rgb; });
  EXPECT_EQ(s.trial_playback.frame, 2);
  controller.Push(ui::SetSaliency{ui::SaliencyMode::kOff});
  s = WaitFor(controller,
              [&](const auto& now) { return now.trial_playback.image.rgb == recorded.rgb; });

  // The report has them, and a third trial whose arm goes away is not kept.
  controller.Push(ui::WriteReport{});
  s = WaitFor(controller, [](const auto& now) { return !now.report_path.empty(); });
  std::ifstream report(s.report_path);
  const std::string html((std::istreambuf_iterator<char>(report)),
                         std::istreambuf_iterator<char>());
  EXPECT_THAT(html, HasSubstr("Trials on the real arm"));
  EXPECT_THAT(html, HasSubstr("1 of 2"));
  EXPECT_THAT(html, HasSubstr("missed the toast"));
  controller.Push(ui::StartTrials{"baseline", 1});
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kSetUp && now.trial.number == 3;
  });
  // An arm parked far from home (a wrist turned 4 rad) is not swung back by itself.
  std::array<double, 6> parked = worlds::Ur5Arm::kHome;
  parked[4] += 4.0;
  // A real arm cannot jump: after moving the fake's, wait until the studio's view of the arm (its
  // RTDE state) has seen it.
  const auto teleport = [&](const std::array<double, 6>& q) {
    const std::array<float, 3> before = controller.Snapshot().grip_m;
    rig_->robot->Teleport(q);
    WaitFor(controller, [&](const auto& now) {
      return std::hypot(now.grip_m[0] - before[0], now.grip_m[1] - before[1],
                        now.grip_m[2] - before[2]) > 0.01;
    });
  };
  teleport(parked);
  controller.Push(ui::RunTrial{});
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kSetUp && !now.trial.message.empty();
  });
  EXPECT_THAT(s.trial.message, HasSubstr("joint 5 is 4.00 rad from its home pose"));
  EXPECT_THAT(s.trial.message, HasSubstr("with the pendant first"));
  EXPECT_LT(std::abs(rig_->robot->q_rad()[4] - parked[4]), 1e-3) << "it did not move";
  teleport(worlds::Ur5Arm::kHome);
  controller.Push(ui::DismissErrors{});
  controller.Push(ui::RunTrial{});
  s = WaitFor(controller, [](const auto& now) { return now.trial.step >= 2; });
  rig_->robot.reset();  // the arm's controller goes away mid-trial
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kSetUp && !now.trial.message.empty();
  });
  EXPECT_THAT(s.trial.message, HasSubstr("Trial 3 stopped"));
  controller.Push(ui::EndTrials{});
  s = WaitFor(controller, [](const auto& now) { return now.trial.phase == ui::TrialPhase::kNone; });
  ASSERT_EQ(s.real_trials.size(), 1u);
  EXPECT_EQ(s.real_trials[0].trials.size(), 2u);
}

}  // namespace
}  // namespace recon::studio
