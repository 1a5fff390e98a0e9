// The studio on a real cell's path without hardware: a digital twin (cell::TwinCamera drawing the
// tabletop scene with the UR5 where a FakeUrController on loopback TCP says it is), the plate's
// beacon a FakeDwm1001 on a pseudo-terminal reporting through a hidden UWB frame. The Calibrate
// step runs place by place as the teacher (this test) moves the beacon, says when the beacon goes
// silent, and saves a calibration that passes and maps the beacon onto the table.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <Eigen/Geometry>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "app/cli/result_staleness.h"
#include "app/cli/session_summary.h"
#include "app/studio/studio_controller.h"
#include "engine/calib/calibration.h"
#include "engine/core/rng.h"
#include "engine/store/real_trials.h"
#include "engine/store/session.h"
#include "tests/app/twin_rig.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

ui::StudioSnapshot WaitFor(const StudioController& controller,
                           const std::function<bool(const ui::StudioSnapshot&)>& done,
                           double timeout_s = 30) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    ui::StudioSnapshot s = controller.Snapshot();
    if (done(s)) return s;
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "timed out; status: " << s.status << "; prompt: " << s.calibration.prompt
                    << (s.errors.empty() ? "" : "; last error: " + s.errors.back());
      return s;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

class StudioTwinCellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/recon-studio-twin-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
    rig_ = std::make_unique<testing::TwinRig>(dir_ / "twin");
  }
  void TearDown() override {
    rig_.reset();
    fs::remove_all(dir_);
  }

  StudioOptions Options() const {
    StudioOptions options;
    options.session_dir = (dir_ / "session").string();
    options.recent_sessions_file = (dir_ / "recent.json").string();
    options.cell_profile = rig_->profile;
    options.dev_dir = (dir_ / "no-dev").string();
    options.calibration_points = 5;
    options.countdown_s = 0;
    return options;
  }

  fs::path dir_;
  std::unique_ptr<testing::TwinRig> rig_;
};

TEST_F(StudioTwinCellTest, CalibratesPlaceByPlaceAsTheTeacherMovesTheBeacon) {
  StudioController controller(Options());
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.camera_frame > 0; });
  EXPECT_EQ(s.cell_kind, "real");
  EXPECT_EQ(s.camera.width, 1280);
  controller.Push(ui::OpenStep{teach::Step::kCalibrate});
  controller.Push(ui::StartCalibration{});
  s = WaitFor(controller, [](const auto& now) {
    return now.calibration.running && now.calibration.guided && !now.calibration.prompt.empty();
  });
  EXPECT_EQ(s.calibration.points_target, 5);
  EXPECT_EQ(s.busy_with, "the calibration");
  // Nothing else starts meanwhile.
  controller.Push(ui::StartRecording{});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors.back(), HasSubstr("while something else runs"));
  controller.Push(ui::DismissErrors{});

  const std::vector<Eigen::Vector2d> places = {
      {0.35, -0.3}, {0.75, -0.25}, {0.7, 0.2}, {0.4, 0.15}, {0.55, -0.05}};
  std::vector<Eigen::Vector3d> truth;
  const tags::PinholeCamera camera = rig_->scene.TopCamera(1280, 960);
  for (size_t i = 0; i < places.size(); ++i) {
    // The beacon's battery runs flat as it is moved to the third place: the screen says so and
    // nothing is taken; it reports again, and the place is taken.
    if (i == 2) rig_->beacon->Silence(true);
    truth.push_back(rig_->PutPlate(places[i].x(), places[i].y()));
    if (i == 2) {
      s = WaitFor(controller, [](const auto& now) { return now.calibration.beacon_silent; });
      EXPECT_THAT(s.calibration.prompt, HasSubstr("No reading from the beacon"));
      EXPECT_EQ(s.calibration.points_collected, 2);
      // Where the camera sees the tag, drawn over the live view.
      ASSERT_TRUE(s.calibration.tag_seen);
      const Eigen::Vector2d expected = camera.Project(truth.back());
      EXPECT_NEAR(s.calibration.tag_pixel[0], expected.x(), 2.0);
      EXPECT_NEAR(s.calibration.tag_pixel[1], expected.y(), 2.0);
      rig_->beacon->Silence(false);
    }
    s = WaitFor(controller, [&](const auto& now) {
      return now.calibration.points_collected >= static_cast<int>(i + 1) ||
             !now.calibration.running;
    });
    if (i + 1 < places.size()) {
      EXPECT_EQ(s.calibration.points_collected, static_cast<int>(i + 1));
      EXPECT_EQ(s.calibration.taken_pixel.size(), i + 1);
    }
  }
  s = WaitFor(controller,
              [](const auto& now) { return !now.calibration.running && now.calibration.present; });
  EXPECT_TRUE(s.calibration.passed);
  EXPECT_LT(s.calibration.rmse_m, 0.03);
  EXPECT_EQ(s.calibration.residual_m.size(), 5u);
  EXPECT_THAT(s.status, HasSubstr("Calibrated: PASS"));

  // The session keeps the fit, and the beacon now reads where the plate's beacon is on the table.
  const store::Session session =
      store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
  ASSERT_FALSE(session.manifest().calibration_file.empty());
  const calib::CalibrationReport saved = calib::LoadCalibration(
      (fs::path(session.dir()) / session.manifest().calibration_file).string());
  EXPECT_TRUE(saved.passed);
  controller.Push(ui::AssignBeacon{"plate", "plate"});
  const Eigen::Vector3d now_at = rig_->PutPlate(0.6, -0.2);
  s = WaitFor(controller, [&](const auto& now) {
    return now.beacons.size() == 1 && now.beacons[0].reading.size() == 2 &&
           std::abs(now.beacons[0].reading[0] - now_at.x()) < 0.03 &&
           std::abs(now.beacons[0].reading[1] - now_at.y()) < 0.03;
  });
  ASSERT_EQ(s.beacons.size(), 1u);
}

TEST_F(StudioTwinCellTest, CancellingKeepsTheCalibrationTheSessionHad) {
  StudioController controller(Options());
  WaitFor(controller, [](const auto& now) { return now.camera_frame > 0; });
  controller.Push(ui::StartCalibration{});
  rig_->PutPlate(0.4, -0.25);
  ui::StudioSnapshot s =
      WaitFor(controller, [](const auto& now) { return now.calibration.points_collected == 1; });
  controller.Push(ui::CancelCalibration{});
  s = WaitFor(controller, [](const auto& now) { return !now.calibration.running; });
  EXPECT_FALSE(s.calibration.present);
  EXPECT_THAT(s.status, HasSubstr("cancelled"));
  const store::Session session =
      store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
  EXPECT_TRUE(session.manifest().calibration_file.empty());
  EXPECT_FALSE(fs::exists(dir_ / "session" / "calibration.new.json"));
}

TEST_F(StudioTwinCellTest, RunsTrialsOnTheRealArmJudgedByThePersonKeepingEveryJudgedOne) {
  calib::SaveCalibration(testing::TwinCalibration(), (dir_ / "cal.json").string());
  StudioOptions options = Options();
  options.calibration_file = (dir_ / "cal.json").string();
  options.train_steps = 20;
  StudioController controller(options);
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.camera_frame > 0; });
  controller.Push(ui::AssignBeacon{"plate", "plate"});
  // Two keyboard demonstrations: the arm moves up the screen, then is kept.
  for (int take = 0; take < 2; ++take) {
    controller.Push(ui::StartRecording{});
    s = WaitFor(controller, [](const auto& now) { return now.recording; });
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
  // Trial 1: set up, run, stopped by the person after a few steps, judged a success.
  rig_->SetUpLayout(s.trial);
  const int64_t commands = rig_->robot->commands_received();
  controller.Push(ui::RunTrial{});
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
  EXPECT_EQ(log->cell, "real");
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
  EXPECT_EQ(frames.y[0].size(), 3u * 64 * 64);
  EXPECT_EQ(frames.u[0].size(), 7u);
  controller.Push(ui::ShowTrialFrame{"baseline", 1, 2});
  s = WaitFor(controller, [](const auto& now) { return now.trial_playback.frame == 2; });
  EXPECT_EQ(s.trial_playback.frames, trial_one_steps);
  EXPECT_EQ(s.trial_playback.image.width, 64);

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
