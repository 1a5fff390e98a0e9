// The digital twin of a real cell: a camera behind the real Camera interface that draws the
// tabletop scene with the UR5 where its controller (a FakeUrController on loopback TCP, read over
// RTDE) says it is and the objects where a layout file puts them; and a real cell opened on it
// from a profile, which locates its camera from the scene's table tags as it would a real one.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "devices/cell/cell_profile.h"
#include "devices/cell/real_cell.h"
#include "devices/cell/twin_camera.h"
#include "devices/cell/twin_cell.h"
#include "devices/cell/twin_scene.h"
#include "devices/render/mujoco_renderer.h"
#include "devices/robot/fake_ur_controller.h"
#include "engine/core/error.h"
#include "tests/cell/fake_cell_devices.h"

namespace recon::cell {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWidth = 320, kHeight = 240;

class TwinCellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/recon-twin-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// What the twin must show: the scene drawn here with the same layout, joints and gripper.
  RgbImage Expected(const TwinLayout& layout, const worlds::Ur5Joints& q, double opening) {
    TwinScene scene;
    scene.Arrange(layout);
    scene.PoseArm(q, opening);
    return render::MujocoRendererFactory()()->Render(scene.scene(), "top", kWidth, kHeight);
  }

  /// Captures until a frame equals `expected` (the controller's state reaches the camera at
  /// RTDE's rate); the last frame when none did within 5 s.
  static devices::CameraFrame CaptureUntil(TwinCamera& camera, const RgbImage& expected) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    devices::CameraFrame frame;
    do {
      frame = camera.Capture();
      if (frame.image.rgb == expected.rgb) return frame;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    } while (std::chrono::steady_clock::now() < deadline);
    return frame;
  }

  fs::path dir_;
};

TEST_F(TwinCellTest, TheCameraFollowsTheControllersJointsAndGripperAndTheLayoutFile) {
  robot::FakeUrController robot;
  TwinLayout layout;
  const std::string layout_file = (dir_ / "layout.json").string();
  WriteTwinLayout(layout_file, layout);
  devices::SteadyClock clock;
  TwinCamera camera({layout_file, "127.0.0.1", robot.rtde_port(), kWidth, kHeight}, clock);
  EXPECT_THAT(camera.Describe(), HasSubstr("digital twin"));

  const devices::CameraFrame first = CaptureUntil(camera, Expected(layout, robot.q_rad(), 1.0));
  EXPECT_EQ(first.image.width, kWidth);
  EXPECT_EQ(first.image.height, kHeight);
  EXPECT_EQ(first.image.rgb, Expected(layout, robot.q_rad(), 1.0).rgb);

  // The arm moves on the controller: the camera sees it there.
  worlds::Ur5Joints q = robot.q_rad();
  q[0] += 0.5;
  q[1] += 0.3;
  robot.Teleport(q);
  const RgbImage moved = Expected(layout, q, 1.0);
  ASSERT_NE(moved.rgb, first.image.rgb);
  EXPECT_EQ(CaptureUntil(camera, moved).image.rgb, moved.rgb);

  // The gripper closes on the controller (tool output 0).
  robot.HandleScriptLine("set_tool_digital_out(0,True)");
  const RgbImage closed = Expected(layout, q, 0.0);
  ASSERT_NE(closed.rgb, moved.rgb);
  EXPECT_EQ(CaptureUntil(camera, closed).image.rgb, closed.rgb);

  // A person moves the plate and the toast: the layout file changes, and so does the picture.
  layout.plate = {0.5, -0.3};
  layout.toast = {0.6, 0.1};
  WriteTwinLayout(layout_file, layout);
  const RgbImage rearranged = Expected(layout, q, 0.0);
  EXPECT_EQ(CaptureUntil(camera, rearranged).image.rgb, rearranged.rgb);
  EXPECT_GT(camera.Capture().sequence, first.sequence);
}

TEST_F(TwinCellTest, TheArmIsDrawnWhereItWasSeenWhileItsControllerIsGone) {
  auto robot = std::make_unique<robot::FakeUrController>();
  const TwinLayout layout;
  const std::string layout_file = (dir_ / "layout.json").string();
  WriteTwinLayout(layout_file, layout);
  devices::SteadyClock clock;
  TwinCamera camera({layout_file, "127.0.0.1", robot->rtde_port(), kWidth, kHeight}, clock);
  worlds::Ur5Joints q = robot->q_rad();
  q[0] -= 0.4;
  robot->Teleport(q);
  const RgbImage there = Expected(layout, q, 1.0);
  ASSERT_EQ(CaptureUntil(camera, there).image.rgb, there.rgb);
  robot.reset();  // the controller goes away: frames keep coming, the arm where it was
  for (int i = 0; i < 3; ++i) EXPECT_EQ(camera.Capture().image.rgb, there.rgb);
}

TEST_F(TwinCellTest, ARealCellOpenedOnATwinLocatesItsCameraFromTheTableTags) {
  robot::FakeUrController robot;
  const std::unique_ptr<uwb::FakeDwm1001> beacon =
      testing::StillBeacon(0xDECA0000000000A1ull, {1.0, 0.5, 0.1});
  TwinCellDevices devices;
  devices.rtde_port = robot.rtde_port();
  devices.script_port = robot.script_port();
  devices.beacon_ports = {beacon->port()};
  devices.beacon_names = {{"0xDECA0000000000A1", "plate"}};
  const std::string profile_path = WriteTwinCell(dir_.string(), devices, TwinLayout{});

  const CellProfile profile = ReadCellProfile(profile_path);
  EXPECT_EQ(profile.camera.device, "twin:" + (dir_ / "layout.json").string());
  EXPECT_EQ(profile.beacon_tag.id, 10);
  EXPECT_NEAR(profile.beacon_tag.size_m, 0.0352, 1e-9);  // the scene's 4.4 cm tag, 0.8 of it
  RealCell cell(profile);
  ASSERT_TRUE(cell.camera_pose().has_value()) << cell.camera_pose_error();
  EXPECT_EQ(cell.camera_pose()->used_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_LT(cell.camera_pose()->reprojection_rms_px, 1.0);
  const TwinScene scene;
  EXPECT_LT(
      (cell.camera_pose()->camera.position_table_m() - scene.TopCamera(640, 480).position_table_m())
          .norm(),
      0.01);
  const std::vector<CellDeviceStatus> status = cell.Status();
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status[0].kind, "digital twin");
  EXPECT_TRUE(status[0].connected) << status[0].last_error;
}

TEST_F(TwinCellTest, ABadLayoutOrATwinWithoutARobotIsRefusedByName) {
  const std::string layout_file = (dir_ / "layout.json").string();
  const auto refused = [&](const std::string& text) -> std::string {
    std::ofstream(layout_file) << text;
    try {
      ReadTwinLayout(layout_file);
    } catch (const UserError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_THAT(refused(R"({"spoon": [0.5, 0.1]})"),
              ::testing::AllOf(HasSubstr("layout.json"), HasSubstr("spoon"),
                               HasSubstr("known: plate, bowl, toast")));
  EXPECT_THAT(refused(R"({"plate": [0.5]})"),
              ::testing::AllOf(HasSubstr("plate"), HasSubstr("expected [x, y]")));
  EXPECT_THAT(refused(R"({"bowl": [1.5, 0.0]})"),
              ::testing::AllOf(HasSubstr("bowl"), HasSubstr("off the table")));
  EXPECT_THAT(refused("not json"), HasSubstr("not valid JSON"));
  fs::remove(layout_file);
  try {
    ReadTwinLayout(layout_file);
    ADD_FAILURE() << "a missing layout was read";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), ::testing::AllOf(HasSubstr("layout.json"), HasSubstr("missing")));
  }

  // A twin draws the profile's robot: a profile without one is refused, naming the camera.
  WriteTwinLayout(layout_file, TwinLayout{});
  const std::unique_ptr<uwb::FakeDwm1001> beacon =
      testing::StillBeacon(0xDECA0000000000A1ull, {1.0, 0.5, 0.1});
  std::ofstream(dir_ / "tags.json") << R"({"tags": []})";
  std::ofstream(dir_ / "cell.json") << R"({"camera": {"device": "twin:layout.json"},
      "table_tags": "tags.json", "beacons": {"ports": [")"
                                    << beacon->port() << R"("]}})";
  try {
    RealCell cell(ReadCellProfile((dir_ / "cell.json").string()));
    ADD_FAILURE() << "a twin without a robot was opened";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), ::testing::AllOf(HasSubstr("twin:"), HasSubstr("names none")));
  }
  std::ofstream(dir_ / "cell.json") << R"({"camera": {"device": "twin:"},
      "table_tags": "tags.json", "beacons": {"ports": ["/dev/null"]}})";
  EXPECT_THROW(
      {
        try {
          ReadCellProfile((dir_ / "cell.json").string());
        } catch (const UserError& e) {
          EXPECT_THAT(e.what(), ::testing::AllOf(HasSubstr("camera.device"),
                                                 HasSubstr("names its layout file")));
          throw;
        }
      },
      UserError);
}

}  // namespace
}  // namespace recon::cell
