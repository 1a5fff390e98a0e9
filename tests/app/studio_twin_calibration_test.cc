// The studio's Calibrate step on a real cell's path without hardware (a digital twin, see
// studio_twin_cell_test.cc): place by place as the teacher (this test) moves the beacon, saying
// when the beacon goes silent; cancelled; and, when the profile puts the beacon on the arm, by the
// arm carrying it to the places itself. Each saves a calibration that passes and maps the beacon
// onto the table, or keeps the one the session had.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/studio/studio_controller.h"
#include "engine/calib/calibration.h"
#include "engine/safety/ur5_kinematics.h"
#include "engine/store/session.h"
#include "tests/app/studio_twin_fixture.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::StudioTwinCellTest;
using testing::WaitFor;

TEST_F(StudioTwinCellTest, CalibratesPlaceByPlaceAsTheTeacherMovesTheBeacon) {
  StudioController controller(Options());
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.camera_frame > 0; });
  EXPECT_EQ(s.cell_kind, "real");
  EXPECT_EQ(s.camera.width, 1280);
  controller.Push(ui::OpenStep{teach::Step::kCalibrate});
  controller.Push(ui::StartCalibration{});
  s = WaitFor(controller, [](const auto& now) {
    return now.calibration.running && now.calibration.guided &&
           !now.calibration.guided->prompt.empty();
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
      s = WaitFor(controller, [](const auto& now) {
        return now.calibration.guided && now.calibration.guided->beacon_silent;
      });
      const ui::GuidedCalibrationView& live = *s.calibration.guided;
      EXPECT_THAT(live.prompt, HasSubstr("No reading from the beacon"));
      EXPECT_EQ(s.calibration.points_collected, 2);
      EXPECT_EQ(live.points_taken, 2);
      // Where the camera sees the tag, drawn over the live view.
      ASSERT_TRUE(live.tag_seen);
      const Eigen::Vector2d expected = camera.Project(truth.back());
      EXPECT_NEAR(live.tag_pixel[0], expected.x(), 2.0);
      EXPECT_NEAR(live.tag_pixel[1], expected.y(), 2.0);
      rig_->beacon->Silence(false);
    }
    s = WaitFor(controller, [&](const auto& now) {
      return now.calibration.points_collected >= static_cast<int>(i + 1) ||
             !now.calibration.running;
    });
    if (i + 1 < places.size()) {
      EXPECT_EQ(s.calibration.points_collected, static_cast<int>(i + 1));
      ASSERT_TRUE(s.calibration.guided.has_value());
      EXPECT_EQ(s.calibration.guided->taken_pixel.size(), i + 1);
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

// A profile that puts the beacon on the arm's tool: nobody moves anything. The arm carries the
// beacon (here a thread keeps the fake beacon where the fake arm's tool is, 3 cm above the tool
// point) to the places, holds it there, and the fit finds the hidden UWB frame.
TEST_F(StudioTwinCellTest, CalibratesByTheArmWhenTheProfilePutsTheBeaconOnIt) {
  {
    std::ifstream in(rig_->profile);
    nlohmann::json profile = nlohmann::json::parse(in);
    profile["beacon_on_arm"] = {{"offset_m", {0.0, 0.0, 0.03}}};
    std::ofstream(rig_->profile) << profile.dump(2);
  }
  const Eigen::Vector3d offset(0.0, 0.0, 0.03);
  std::atomic<bool> follow{true};
  std::thread beacon_on_tool([&] {
    while (follow) {
      rig_->beacon->MoveTo(safety::Ur5ToolPoint(rig_->robot->q_rad(), 0.1) + offset);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  StudioOptions options = Options();
  options.calibration_points = 3;
  StudioController controller(options);
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.camera_frame > 0; });
  controller.Push(ui::AssignBeacon{"plate", "plate"});
  controller.Push(ui::OpenStep{teach::Step::kCalibrate});
  const int64_t commands = rig_->robot->commands_received();
  controller.Push(ui::StartCalibration{});
  s = WaitFor(controller, [](const auto& now) {
    return now.calibration.guided &&
           now.calibration.guided->prompt.find("carries the beacon") != std::string::npos;
  });
  EXPECT_EQ(s.calibration.points_target, 3);
  s = WaitFor(
      controller,
      [](const auto& now) { return !now.calibration.running && now.calibration.present; }, 90);
  follow = false;
  beacon_on_tool.join();
  EXPECT_TRUE(s.calibration.passed);
  EXPECT_EQ(s.calibration.residual_m.size(), 3u);
  EXPECT_GT(rig_->robot->commands_received(), commands + 20) << "the arm was not driven";
  // The saved fit maps the beacon's UWB readings onto the table where the arm held it.
  const store::Session session =
      store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
  const calib::CalibrationReport fit = calib::LoadCalibration(
      (fs::path(session.dir()) / session.manifest().calibration_file).string());
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.35, -0.2, 0.1), Eigen::Vector3d(0.7, 0.25, 0.2)}) {
    EXPECT_LT((fit.transform.Apply(testing::TwinUwbFrame().Apply(p)) - p).norm(), 0.03)
        << p.transpose();
  }
}

}  // namespace
}  // namespace recon::studio
