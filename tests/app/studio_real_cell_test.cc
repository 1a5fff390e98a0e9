// The studio teaching in a real cell (recon-studio --cell PROFILE) over real transports, no
// mocks: the camera is an image sequence in a temporary folder, the plate beacon a FakeDwm1001
// on a pseudo-terminal, the UR5 a FakeUrController on loopback TCP. The Cell step shows the
// devices' live status; the keyboard drives the real arm through the resolved-rate mapping and
// the safety envelope; a demonstration is committed with the real devices' samples; the e-stop
// reaches the controller.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "app/studio/studio_controller.h"
#include "devices/robot/fake_ur_controller.h"
#include "devices/uwb/fake_dwm1001.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/store/session.h"
#include "tests/app/controller_wait.h"
#include "tests/cell/fake_cell_devices.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr uint64_t kPlateId = 0xDECA0000000000A1ull;
const Eigen::Vector3d kPlateUwb_m(1.25, 0.5, 0.1);

ui::StudioSnapshot WaitFor(const StudioController& controller,
                           const std::function<bool(const ui::StudioSnapshot&)>& done,
                           double timeout_s = 20) {
  return testing::WaitForSnapshot(controller, done, timeout_s);
}

class StudioRealCellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/recon-studio-real-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
    cell::testing::WriteFrameFolder(dir_ / "frames",
                                    RgbImage{160, 120, std::vector<uint8_t>(160 * 120 * 3, 90)});
    std::ofstream(dir_ / "tags.json") << R"({"tags": []})";
    beacon_ = cell::testing::StillBeacon(kPlateId, kPlateUwb_m);
    robot_ = std::make_unique<robot::FakeUrController>();
    std::ofstream(dir_ / "cell.json")
        << R"({"camera": {"device": "frames"}, "table_tags": "tags.json",
               "beacons": {"ports": [")"
        << beacon_->port() << R"("], "mode": "tlv", "names": {"0xDECA0000000000A1": "plate"}},
               "robot": {"host": "127.0.0.1", "rtde_port": )"
        << robot_->rtde_port() << R"(, "script_port": )" << robot_->script_port() << "}}";
    // The UWB frame is the table frame moved 1 m along x: the plate reads at (0.25, 0.5).
    std::vector<calib::CalibrationPoint> points;
    for (const Eigen::Vector3d& tag :
         {Eigen::Vector3d(0.2, -0.3, 0.0), Eigen::Vector3d(0.6, -0.2, 0.0),
          Eigen::Vector3d(0.5, 0.4, 0.0), Eigen::Vector3d(0.3, 0.3, 0.0)}) {
      points.push_back({tag, tag + Eigen::Vector3d(1.0, 0.0, 0.0)});
    }
    calib::SaveCalibration(calib::Calibrate(points), (dir_ / "cal.json").string());
  }
  void TearDown() override {
    robot_.reset();
    beacon_.reset();
    fs::remove_all(dir_);
  }

  StudioOptions Options() const {
    StudioOptions options;
    options.session_dir = (dir_ / "session").string();
    options.recent_sessions_file = (dir_ / "recent.json").string();
    options.cell_profile = (dir_ / "cell.json").string();
    options.calibration_file = (dir_ / "cal.json").string();
    options.dev_dir = (dir_ / "no-dev").string();
    options.countdown_s = 0;  // a person's take starts at once
    return options;
  }

  fs::path dir_;
  std::unique_ptr<uwb::FakeDwm1001> beacon_;
  std::unique_ptr<robot::FakeUrController> robot_;
};

TEST_F(StudioRealCellTest, TeachesADemonstrationOnTheRealDevicesAndTheEStopReachesTheRobot) {
  const std::array<double, 6> home = robot_->q_rad();
  StudioController controller(Options());
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) {
    return now.camera_frame > 0 && now.beacons.size() == 1 && now.beacons[0].reading.size() == 2;
  });
  EXPECT_EQ(s.cell_kind, "real");
  // The Cell step: each real device with its live status.
  std::map<std::string, ui::DeviceView> rows;
  for (const ui::DeviceView& d : s.devices) rows[d.role] = d;
  ASSERT_EQ(rows.count("camera"), 1u);
  ASSERT_EQ(rows.count("beacons"), 1u);
  ASSERT_EQ(rows.count("arm"), 1u);
  EXPECT_TRUE(rows["camera"].connected) << rows["camera"].last_error;
  EXPECT_TRUE(rows["beacons"].connected) << rows["beacons"].last_error;
  EXPECT_TRUE(rows["arm"].connected) << rows["arm"].last_error;
  EXPECT_EQ(rows["beacons"].detail, beacon_->port());
  EXPECT_THAT(rows["camera"].detail, HasSubstr("no camera pose"));  // no table tags in view
  EXPECT_EQ(s.camera.width, 160);
  // The beacon through the attached calibration, in the table frame.
  EXPECT_NEAR(s.beacons[0].reading[0], 0.25, 1e-6);
  EXPECT_NEAR(s.beacons[0].reading[1], 0.5, 1e-6);
  // A real cell has no scripted teacher.
  for (const ui::TeleopChoice& c : s.teleop_choices) {
    if (c.mode == ui::TeleopMode::kScripted) {
      EXPECT_FALSE(c.available);
    }
  }
  EXPECT_EQ(s.teleop, ui::TeleopMode::kKeyboard);
  controller.Push(ui::SetTeleopMode{ui::TeleopMode::kScripted});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors.back(), HasSubstr("a real cell has no scripted teacher"));
  EXPECT_EQ(s.teleop, ui::TeleopMode::kKeyboard);

  controller.Push(ui::AssignBeacon{"plate", "plate"});
  controller.Push(ui::StartRecording{});
  s = WaitFor(controller, [](const auto& now) { return now.recording; });
  const std::array<float, 3> start = s.grip_m;
  ui::TeleopInput up;  // without a camera pose: up on screen is table +y
  up.screen_up = 1;
  controller.Push(up);
  s = WaitFor(controller, [&](const auto& now) {
    return now.grip_m[1] > start[1] + 0.02 && now.recording_samples >= 5;
  });
  EXPECT_NEAR(s.grip_m[0], start[0], 0.01);  // the mapping holds the other axes
  EXPECT_NEAR(s.grip_m[2], start[2], 0.01);
  EXPECT_GT(s.safety.commands, 0);
  EXPECT_EQ(s.safety.limits, "1 rad/s, 5 rad/s^2, tool floor 5 mm, watchdog 200 ms");
  controller.Push(ui::TeleopInput{});
  controller.Push(ui::StopRecording{});
  s = WaitFor(controller, [](const auto& now) { return !now.recording && !now.episodes.empty(); });
  ASSERT_EQ(s.episodes.size(), 1u);
  EXPECT_GE(s.episodes[0].samples, 5);
  bool moved = false;
  for (int i = 0; i < 6; ++i) moved |= std::abs(robot_->q_rad()[i] - home[i]) > 0.01;
  EXPECT_TRUE(moved) << "the fake UR5's joints never moved";

  // What was recorded: the real devices' samples with the task's shapes.
  const store::Session session =
      store::Session::Open((dir_ / "session").string(), store::Session::Access::kReadOnly);
  EXPECT_EQ(session.manifest().cell, "real");
  const store::DemoRecord demo = session.ReadDemo(s.episodes[0].name);
  ASSERT_FALSE(demo.episode.samples.empty());
  const Sample& first = demo.episode.samples.front();
  EXPECT_EQ(first.x.size(), 7u);
  EXPECT_EQ(first.y.size(), 3u * 64 * 64);
  EXPECT_FLOAT_EQ(first.y[0], 90.0f);  // the camera's grey
  ASSERT_EQ(first.b.size(), 2u);
  EXPECT_NEAR(first.b[0], 0.25, 1e-6);
  EXPECT_EQ(first.u.size(), 7u);
  EXPECT_EQ(demo.meta.source, "keyboard-teleop");

  // The e-stop reaches the robot: a recording under way ends and the controller is told to stop.
  controller.Push(ui::StartRecording{});
  controller.Push(up);
  s = WaitFor(controller, [](const auto& now) { return now.recording_samples >= 3; });
  controller.Push(ui::EmergencyStop{true, "test"});
  s = WaitFor(controller, [](const auto& now) { return now.safety.estop && !now.recording; });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (double v : robot_->qd_rad_s()) EXPECT_NEAR(v, 0.0, 1e-6);
  EXPECT_EQ(s.episodes.size(), 1u);                  // the stopped take was not kept
  EXPECT_EQ(s.safety.estop_reason, "test");          // the guarded arm's own latch says so
  EXPECT_THAT(s.pending_take, HasSubstr("e-stop"));  // set aside for the teacher to decide
  controller.Push(ui::DiscardRecording{});
  controller.Push(ui::RunRollouts{1});
  s = WaitFor(controller, [](const auto& now) { return now.errors.size() >= 2; });
  EXPECT_THAT(s.errors.back(), HasSubstr("e-stop is engaged"));
  controller.Push(ui::EmergencyStop{false, ""});
  s = WaitFor(controller, [](const auto& now) { return !now.safety.estop; });
  EXPECT_FALSE(s.safety.estop);

  // Calibrating needs the camera's pose, which a view without the table's tags cannot give.
  const size_t errors = s.errors.size();
  controller.Push(ui::StartCalibration{});
  s = WaitFor(controller, [&](const auto& now) { return now.errors.size() > errors; });
  EXPECT_THAT(s.errors.back(), HasSubstr("the camera's pose in the table frame is unknown"));
  EXPECT_FALSE(s.calibration.running);
}

TEST_F(StudioRealCellTest, ABadProfileOrASessionOfAnotherCellIsRefusedByName) {
  std::ofstream(dir_ / "bad.json") << R"({"camera": {"device": 7}})";
  StudioOptions options = Options();
  options.cell_profile = (dir_ / "bad.json").string();
  try {
    StudioController controller(options);
    ADD_FAILURE() << "a bad profile was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json"));
    EXPECT_THAT(e.what(), HasSubstr("camera.device"));
  }
  // A session taught in the simulated cell comes to a real cell only for trials on its arm: a
  // cell without one refuses it, naming why.
  StudioOptions sim = Options();
  sim.cell_profile.clear();
  sim.calibration_file.clear();
  sim.real_time = false;
  { StudioController controller(sim); }
  std::ofstream(dir_ / "no-arm.json")
      << R"({"camera": {"device": "frames"}, "table_tags": "tags.json",
             "beacons": {"ports": [")"
      << beacon_->port() << R"("], "mode": "tlv", "names": {"0xDECA0000000000A1": "plate"}}})";
  StudioOptions no_arm = Options();
  no_arm.cell_profile = (dir_ / "no-arm.json").string();
  no_arm.calibration_file.clear();
  try {
    StudioController controller(no_arm);
    ADD_FAILURE() << "a simulated session was opened in a real cell without an arm";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("taught in the simulated cell"));
    EXPECT_THAT(e.what(), HasSubstr("no arm"));
  }
  // And a session taught on a real cell is not opened in the simulated one.
  StudioOptions real = Options();
  real.session_dir = (dir_ / "real-session").string();
  real.calibration_file.clear();
  { StudioController controller(real); }
  real.cell_profile.clear();
  try {
    StudioController controller(real);
    ADD_FAILURE() << "a real cell's session was opened in the simulated cell";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("taught in a real cell"));
    EXPECT_THAT(e.what(), HasSubstr("--cell PROFILE"));
  }
}

}  // namespace
}  // namespace recon::studio
