// A real cell over real transports, no mocks: the camera is an image sequence (PNG frames in a
// temporary folder), the beacon a FakeDwm1001 on a pseudo-terminal in TLV mode, the robot a
// FakeUrController on loopback TCP. A cell.json names them; ReadCellProfile and RealCell open
// them; RealCellWorld runs the tabletop task on them.

#include "devices/cell/real_cell.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/image_file.h"
#include "devices/camera/open_camera.h"
#include "devices/camera/table_tags_file.h"
#include "devices/cell/cell_profile.h"
#include "devices/cell/real_cell_world.h"
#include "devices/robot/fake_ur_controller.h"
#include "devices/robot/ur_arm.h"
#include "devices/tags/pinhole_camera.h"
#include "devices/uwb/fake_dwm1001.h"
#include "engine/core/error.h"
#include "engine/worlds/ur5_arm.h"
#include "tests/cell/fake_cell_devices.h"
#include "tests/tags/synthetic_scene.h"

namespace recon::cell {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr uint64_t kPlateId = 0xDECA0000000000A1ull;
// Whole millimetres: TLV carries positions as integer mm, so the reading is exact.
const Eigen::Vector3d kPlateUwb_m(1.234, 0.567, 0.1);

void Sleep(double seconds) { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }

/// Calls `f` until it returns true or `seconds` pass.
bool Eventually(const std::function<bool()>& f, double seconds = 3.0) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (f()) return true;
    Sleep(0.01);
  }
  return f();
}

/// Four quadrants of known colours, 160 x 120: at 64 x 64 each quadrant is exactly 32 x 32
/// output pixels (160 / 64 = 2.5 and 120 / 64 = 1.875 columns and rows per pixel).
RgbImage Quadrants() {
  RgbImage image{160, 120, std::vector<uint8_t>(160 * 120 * 3)};
  const uint8_t colours[4][3] = {{200, 40, 90}, {10, 220, 30}, {60, 70, 250}, {255, 255, 0}};
  for (int r = 0; r < 120; ++r) {
    for (int c = 0; c < 160; ++c) {
      const uint8_t* colour = colours[(r >= 60 ? 2 : 0) + (c >= 80 ? 1 : 0)];
      for (int ch = 0; ch < 3; ++ch)
        image.rgb[(static_cast<size_t>(r) * 160 + c) * 3 + ch] = colour[ch];
    }
  }
  return image;
}

std::unique_ptr<uwb::FakeDwm1001> PlateBeacon() {
  return testing::StillBeacon(kPlateId, kPlateUwb_m);
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

class RealCellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/recon-real-cell-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A folder of `count` copies of `image` (frame_000.png, ...).
  void WriteFrames(const std::string& folder, const RgbImage& image, int count = 3) {
    testing::WriteFrameFolder(dir_ / folder, image, count);
  }

  /// A cell.json whose camera is the folder "frames" (relative), with the beacon and, when
  /// given, the robot. `extra` is spliced into the top-level object.
  std::string WriteProfile(const uwb::FakeDwm1001& beacon, const robot::FakeUrController* robot,
                           const std::string& extra = "") {
    std::string text = R"({"camera": {"device": "frames"}, "table_tags": "tags.json",
        "beacons": {"ports": [")" +
                       beacon.port() +
                       R"("], "mode": "tlv", "names": {"0xDECA0000000000A1": "plate"}})";
    if (robot != nullptr) {
      text += R"(, "robot": {"host": "127.0.0.1", "rtde_port": )" +
              std::to_string(robot->rtde_port()) +
              ", \"script_port\": " + std::to_string(robot->script_port()) + "}";
    }
    text += extra + "}";
    const fs::path path = dir_ / "cell.json";
    WriteText(path, text);
    return path.string();
  }

  fs::path dir_;
};

calib::RigidTransform SomeCalibration() {
  calib::RigidTransform t;
  t.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation = Eigen::Vector3d(-0.8, 0.3, -0.75);
  return t;
}

TEST_F(RealCellTest, OpensEveryDeviceAndTeachesTheTabletopTaskOnThem) {
  WriteFrames("frames", Quadrants());
  auto beacon = PlateBeacon();
  robot::FakeUrController controller;
  RealCell cell(ReadCellProfile(WriteProfile(*beacon, &controller)));
  ASSERT_NE(cell.camera().WaitForFrame(-1, 3.0), nullptr) << cell.camera().error();
  EXPECT_FALSE(cell.intrinsics().has_value());
  EXPECT_FALSE(cell.camera_pose().has_value());
  EXPECT_THAT(cell.camera_pose_error(), HasSubstr("no camera calibration"));

  const std::vector<CellDeviceStatus> status = cell.Status();
  ASSERT_EQ(status.size(), 3u);
  EXPECT_EQ(status[0].role, "camera");
  EXPECT_EQ(status[0].kind, "image sequence");
  EXPECT_EQ(status[0].detail, (dir_ / "frames").string()) << "resolved against cell.json";
  EXPECT_EQ(status[1].role, "beacons");
  EXPECT_EQ(status[1].detail, beacon->port());
  EXPECT_EQ(status[2].role, "arm");
  EXPECT_EQ(status[2].detail, "127.0.0.1");
  for (const CellDeviceStatus& row : status) {
    EXPECT_TRUE(row.connected) << row.role << ": " << row.last_error;
    EXPECT_EQ(row.last_error, "") << row.role;
  }
  const auto frame = cell.LatestFrame();
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->image.width, 160);

  RealCellWorldOptions options;
  options.uwb_to_table = SomeCalibration();
  const auto world = MakeRealCellWorld(cell, options);
  EXPECT_EQ(world->Name(), "tabletop");
  EXPECT_EQ(world->Spec().ToString(), "x 7, y 3x64x64, b 2, u 7");
  EXPECT_EQ(world->EpisodeLength(), 200);
  EXPECT_DOUBLE_EQ(world->StepSeconds(), 0.1);
  EXPECT_EQ(world->PlaySamplesPerScenario(), 10);
  EXPECT_FALSE(world->HasSuccess());
  EXPECT_EQ(world->EpisodeMetric(), 0.0);
  EXPECT_THAT(world->MetricName(), HasSubstr("not measured in a real cell"));
  EXPECT_THAT([&] { world->ExpertAction(); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("keyboard or a gamepad")));

  world->Reset(1);
  const worlds::Observation o = world->Observe();
  ASSERT_EQ(o.x.size(), 7u);
  ASSERT_EQ(o.y.size(), 3u * 64 * 64);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(o.x[i], 0.0, 1e-6) << "the fake starts at home";
  EXPECT_FLOAT_EQ(o.x[6], 1.0f) << "gripper open";
  // Channel planes of the quadrant colours: (row, col) in each quadrant.
  const auto y = [&](int ch, int r, int c) { return o.y[(ch * 64 + r) * 64 + c]; };
  EXPECT_NEAR(y(0, 5, 5), 200, 1e-3);
  EXPECT_NEAR(y(1, 5, 5), 40, 1e-3);
  EXPECT_NEAR(y(2, 5, 5), 90, 1e-3);
  EXPECT_NEAR(y(1, 31, 32), 220, 1e-3);
  EXPECT_NEAR(y(2, 32, 31), 250, 1e-3);
  EXPECT_NEAR(y(0, 63, 63), 255, 1e-3);
  EXPECT_NEAR(y(2, 63, 63), 0, 1e-3);

  // The beacon: the fake's UWB position through the calibration.
  std::vector<float> b;
  ASSERT_TRUE(Eventually([&] {
    try {
      b = world->BeaconReading();
      return true;
    } catch (const UserError&) {
      return false;
    }
  })) << cell.beacons().Describe();
  const Eigen::Vector3d expected = SomeCalibration().Apply(kPlateUwb_m);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_NEAR(b[0], expected.x(), 1e-6);
  EXPECT_NEAR(b[1], expected.y(), 1e-6);
  const PlaySample play = world->SamplePlay();
  EXPECT_EQ(play.x.size(), 7u);
  EXPECT_EQ(play.y, o.y);
  EXPECT_NEAR(play.b[0], expected.x(), 1e-6);

  // Motion: joint 0 forward and the gripper closed, at the real 10 Hz.
  const double start_s = cell.clock().NowSeconds();
  for (int i = 0; i < 6; ++i) world->Step({0.3f, 0, 0, 0, 0, 0, 1.0f});
  EXPECT_GE(cell.clock().NowSeconds() - start_s, 0.5) << "six steps span five periods";
  ASSERT_TRUE(controller.last_speedj().has_value());
  EXPECT_NEAR(controller.last_speedj()->velocity_rad_s[0], 0.3, 1e-6);  // 0.3f
  EXPECT_GT(controller.q_rad()[0], worlds::Ur5Arm::kHome[0] + 0.05);
  for (int i = 1; i < 6; ++i) EXPECT_NEAR(controller.q_rad()[i], worlds::Ur5Arm::kHome[i], 1e-6);
  EXPECT_TRUE(controller.tool_output(0)) << "the gripper was closed";
  ASSERT_TRUE(Eventually([&] { return world->Observe().x[0] > 0.05f; }));
  EXPECT_FLOAT_EQ(world->Observe().x[6], 0.0f);

  // A NaN is a stop (stopj), never a speedj.
  const auto before = controller.last_speedj();
  world->Step({NAN, 0, 0, 0, 0, 0, 1.0f});
  EXPECT_EQ(controller.last_speedj()->velocity_rad_s, before->velocity_rad_s);
  EXPECT_TRUE(Eventually([&] { return std::abs(controller.qd_rad_s()[0]) < 1e-9; }))
      << "still moving after a NaN action";
  EXPECT_EQ(cell.arm()->stats().non_finite, 1);
}

TEST_F(RealCellTest, ARobotThatIsGoneIsAnErrorNamingTheHost) {
  WriteFrames("frames", Quadrants());
  auto beacon = PlateBeacon();
  robot::FakeUrController controller;
  RealCell cell(ReadCellProfile(WriteProfile(*beacon, &controller)));
  ASSERT_NE(cell.camera().WaitForFrame(-1, 3.0), nullptr);
  const auto world = MakeRealCellWorld(cell, {});
  world->Observe();
  world->Step({0.1f, 0, 0, 0, 0, 0, 0});

  controller.Stop();
  const auto observe_fails = [&] {
    try {
      world->Observe();
      return false;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("UR5 at 127.0.0.1"));
      return true;
    }
  };
  ASSERT_TRUE(Eventually(observe_fails));
  EXPECT_THAT(
      [&] {
        world->Step({0.1f, 0, 0, 0, 0, 0, 0});
      },
      ::testing::ThrowsMessage<UserError>(HasSubstr("127.0.0.1")));
  const std::vector<CellDeviceStatus> status = cell.Status();
  ASSERT_EQ(status.size(), 3u);
  EXPECT_FALSE(status[2].connected);
  EXPECT_NE(status[2].last_error, "");
  // The cell still closes cleanly: its destructor's stop fails quietly.
}

TEST_F(RealCellTest, WithoutCalibrationOrRobotTheCellStillOpensAndSaysWhatIsMissing) {
  WriteFrames("frames", Quadrants());
  auto beacon = PlateBeacon();
  RealCell cell(ReadCellProfile(WriteProfile(*beacon, nullptr)));
  EXPECT_EQ(cell.arm(), nullptr);
  ASSERT_NE(cell.camera().WaitForFrame(-1, 3.0), nullptr);
  const std::vector<CellDeviceStatus> status = cell.Status();
  ASSERT_EQ(status.size(), 2u) << "no arm row without a robot";
  EXPECT_THAT([&] { MakeRealCellWorld(cell, {}); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("names no robot")));

  // The world without a calibration refuses the beacon (the arm here is a fake controller).
  robot::FakeUrController controller;
  robot::UrArm::Options arm_options;
  arm_options.host = "127.0.0.1";
  arm_options.rtde_port = controller.rtde_port();
  arm_options.script_port = controller.script_port();
  robot::UrArm arm(arm_options);
  RealCellWorld world(cell.camera(), cell.beacons(), arm, cell.clock(), {});
  EXPECT_THAT([&] { world.BeaconReading(); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("calibrate the cell first")));
  RealCellWorldOptions none;
  none.placement = "none";
  RealCellWorld baseline(cell.camera(), cell.beacons(), arm, cell.clock(), none);
  EXPECT_EQ(baseline.Spec().b_dim, 0);
  EXPECT_TRUE(baseline.BeaconReading().empty());
  RealCellWorldOptions bad;
  bad.placement = "bowl";
  EXPECT_THROW(RealCellWorld(cell.camera(), cell.beacons(), arm, cell.clock(), bad), UserError);
}

TEST_F(RealCellTest, AFolderCameraThatDisappearsIsReportedAndNamed) {
  WriteFrames("frames", Quadrants());
  auto beacon = PlateBeacon();
  robot::FakeUrController controller;
  RealCellOptions options;
  options.camera.retry_period_s = 0.05;
  RealCell cell(ReadCellProfile(WriteProfile(*beacon, &controller)), options);
  ASSERT_NE(cell.camera().WaitForFrame(-1, 3.0), nullptr);
  const auto world = MakeRealCellWorld(cell, {});
  world->Observe();

  camera::SilenceOpenCvLogging();  // imread's own warning about the missing file
  fs::remove_all(dir_ / "frames");
  ASSERT_TRUE(Eventually([&] { return !cell.camera().error().empty(); }));
  EXPECT_GT(cell.camera().capture_errors(), 0);
  const std::string folder = (dir_ / "frames").string();
  EXPECT_THAT([&] { world->Observe(); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("camera " + folder)));
  EXPECT_THAT([&] { cell.LatestFrame(); }, ::testing::ThrowsMessage<UserError>(HasSubstr(folder)));
  const CellDeviceStatus camera = cell.Status()[0];
  EXPECT_FALSE(camera.connected);
  EXPECT_NE(camera.last_error, "");
}

TEST_F(RealCellTest, ASilentOrMissingBeaconIsAnErrorNamingIt) {
  WriteFrames("frames", Quadrants());
  auto beacon = PlateBeacon();
  robot::FakeUrController controller;
  RealCell cell(ReadCellProfile(WriteProfile(*beacon, &controller)));
  RealCellWorldOptions options;
  options.uwb_to_table = SomeCalibration();
  options.plate_beacon = "bowl";  // a name no beacon has: nothing ever reports
  const auto absent = MakeRealCellWorld(cell, options);
  EXPECT_THAT([&] { absent->BeaconReading(); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("'bowl' has not reported")));

  options.plate_beacon = "plate";
  options.beacon_max_age_s = 0.3;
  const auto world = MakeRealCellWorld(cell, options);
  ASSERT_TRUE(Eventually([&] {
    try {
      world->BeaconReading();
      return true;
    } catch (const UserError&) {
      return false;
    }
  }));
  beacon->Unplug();
  const auto silent = [&] {
    try {
      world->BeaconReading();
      return false;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr(beacon->port()));
      return std::string(e.what()).find("silent") != std::string::npos;
    }
  };
  EXPECT_TRUE(Eventually(silent));
  bool port_down = false;
  for (const CellDeviceStatus& row : cell.Status()) {
    if (row.role == "beacons") port_down = !row.connected && !row.last_error.empty();
  }
  EXPECT_TRUE(port_down);
}

TEST_F(RealCellTest, TheCameraPoseIsEstimatedFromTheTableTagsAtOpen) {
  // A synthetic top-down view of four table tags through a known pinhole camera.
  tags::testing::SceneCamera scene;
  scene.position_m = {0.05, -0.02, 0.9};
  std::vector<tags::testing::PlacedTag> placed;
  std::vector<camera::TableTag> table_tags;
  const double corners[4][2] = {{0.25, 0.18}, {-0.25, 0.18}, {-0.25, -0.18}, {0.25, -0.18}};
  for (int id = 0; id < 4; ++id) {
    const Eigen::Vector3d center(corners[id][0], corners[id][1], 0.0);
    placed.push_back({id, center, 0.0, 0.08});
    table_tags.push_back({id, center, 0.08, 0.0});
  }
  tags::testing::SceneOptions render;
  render.supersample = 1;
  WriteFrames("frames", tags::testing::RenderScene(scene, placed, {}, render), 2);
  camera::WriteTableTags((dir_ / "tags.json").string(), table_tags);
  const tags::PinholeCamera truth = tags::PinholeCamera::FromMujoco(
      scene.fovy_deg, scene.width, scene.height, scene.position_m, scene.table_R_mujoco);
  camera::WriteCameraCalibration((dir_ / "camera.yaml").string(),
                                 camera::CameraCalibration::FromIntrinsics(truth.intrinsics()));
  auto beacon = PlateBeacon();
  std::string profile = WriteProfile(*beacon, nullptr);
  std::string text = R"({"camera": {"device": "frames", "calibration": "camera.yaml"},
      "table_tags": "tags.json", "beacons": {"ports": [")" +
                     beacon->port() + R"("], "mode": "tlv"}})";
  WriteText(profile, text);

  RealCell cell(ReadCellProfile(profile));
  ASSERT_TRUE(cell.intrinsics().has_value());
  ASSERT_TRUE(cell.camera_pose().has_value()) << cell.camera_pose_error();
  EXPECT_EQ(cell.camera_pose()->used_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_LT((cell.camera_pose()->camera.position_table_m() - scene.position_m).norm(), 0.01);
  EXPECT_EQ(cell.camera_pose_error(), "");

  // Frames without the tags: the cell opens all the same, and says why there is no pose.
  fs::remove_all(dir_ / "frames");
  RgbImage blank{640, 480, std::vector<uint8_t>(640 * 480 * 3, 255)};
  WriteFrames("frames", blank, 2);
  RealCell blind(ReadCellProfile(profile));
  EXPECT_FALSE(blind.camera_pose().has_value());
  EXPECT_THAT(blind.camera_pose_error(), HasSubstr("table tags"));
}

TEST_F(RealCellTest, DevicesThatCannotBeOpenedAreNamed) {
  WriteFrames("frames", Quadrants());
  auto beacon = PlateBeacon();
  // A robot that is not there: a controller's ports, closed again.
  auto gone = std::make_unique<robot::FakeUrController>();
  const std::string profile_path = WriteProfile(*beacon, gone.get());
  gone->Stop();
  RealCellOptions options;
  options.robot_timeout_s = 0.5;
  EXPECT_THAT([&] { RealCell cell(ReadCellProfile(profile_path), options); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("robot 127.0.0.1")));

  // A camera folder that does not exist.
  fs::remove_all(dir_ / "frames");
  const std::string no_robot = WriteProfile(*beacon, nullptr);
  EXPECT_THAT(
      [&] { RealCell cell(ReadCellProfile(no_robot)); },
      ::testing::ThrowsMessage<UserError>(HasSubstr("camera " + (dir_ / "frames").string())));
}

TEST(AreaAverageTest, EachOutputPixelIsTheMeanOfTheAreaItCovers) {
  // 3 x 3 grey levels 0..8 (one channel repeated) down to 2 x 2: each output covers 1.5 x 1.5
  // input pixels, the middle row and column half; the mean is rounded to a whole level, as a
  // session stores images in 8 bits.
  RgbImage image{3, 3, {}};
  for (int v = 0; v < 9; ++v)
    image.rgb.insert(image.rgb.end(), {uint8_t(v), uint8_t(v), uint8_t(v)});
  const std::vector<float> y = AreaAveragedChannelsFirst(image, 2);
  ASSERT_EQ(y.size(), 12u);
  // Top-left: (0 + 0.5*1 + 0.5*3 + 0.25*4) / 2.25 = 1.33.
  EXPECT_EQ(y[0], 1.0f);
  // Bottom-right: (0.25*4 + 0.5*5 + 0.5*7 + 8) / 2.25 = 6.67.
  EXPECT_EQ(y[3], 7.0f);
  EXPECT_EQ(y[4 + 3], y[3]) << "every channel alike";
  // Upsampling copies: a 1 x 1 image becomes a flat 16 x 16 one.
  const std::vector<float> flat = AreaAveragedChannelsFirst(RgbImage{1, 1, {7, 8, 9}}, 16);
  EXPECT_NEAR(flat[0], 7, 1e-5);
  EXPECT_NEAR(flat[16 * 16 + 100], 8, 1e-5);
  EXPECT_NEAR(flat[2 * 16 * 16 + 255], 9, 1e-5);
}

}  // namespace
}  // namespace recon::cell
