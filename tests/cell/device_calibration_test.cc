// Calibration with real devices, end to end over real transports: the camera is an image
// sequence (frames rendered from the simulated cell and written as PNG files), the beacon a
// FakeDwm1001 on a pseudo-terminal behind a BeaconHub, and the UWB frame a hidden transform the
// calibration must recover.

#include "devices/cell/device_calibration.h"

#include <mujoco/mujoco.h>

#include <stdlib.h>
#include <Eigen/Geometry>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "devices/camera/image_sequence_camera.h"
#include "devices/cell/scene_camera.h"
#include "devices/render/mujoco_renderer.h"
#include "devices/uwb/beacon_hub.h"
#include "devices/uwb/fake_dwm1001.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/report/image_png.h"
#include "engine/worlds/scene_assets.h"
#include "engine/worlds/tag_textures.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::cell {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWidth = 640, kHeight = 480, kPoses = 6;

/// The simulated cell photographed with the beacon at kPoses places, as a folder of PNG
/// frames (the first pose twice: the first frame gives the camera's pose), and the truth.
struct RenderedSession {
  fs::path folder;
  std::vector<Eigen::Vector3d> beacon_truth;
  tags::CameraIntrinsics intrinsics;
  tags::PinholeCamera true_camera{
      tags::CameraIntrinsics::FromFovy(45, 4, 4), {0, 0, 1}, Eigen::Matrix3d::Identity()};
  double beacon_height_m = 0;
};

RenderedSession Render(const fs::path& folder) {
  RenderedSession session;
  session.folder = folder;
  worlds::MujocoModel scene = worlds::LoadScene("tabletop");
  worlds::PaintTagTextures(scene);
  const mjModel* m = scene.model();
  mjData* d = scene.data();
  const int plate = mj_name2id(m, mjOBJ_BODY, "plate");
  const int bowl = mj_name2id(m, mjOBJ_BODY, "bowl");
  const int beacon_site = mj_name2id(m, mjOBJ_SITE, "beacon");
  mjtNum* bowl_pos = d->mocap_pos + 3 * m->body_mocapid[bowl];
  bowl_pos[0] = 0.12;  // clear of the beacon's places and of the corner tags
  bowl_pos[1] = 0.0;
  worlds::Ur5Arm arm(scene);
  arm.Reset(worlds::Ur5Arm::kHome);  // out of the camera's way, as the teacher leaves it
  const auto renderer = render::MujocoRendererFactory()();
  Rng rng(17);  // seed 17: the beacon's places on the table
  int frame = 0;
  for (int i = 0; i < kPoses; ++i) {
    mjtNum* plate_pos = d->mocap_pos + 3 * m->body_mocapid[plate];
    plate_pos[0] = rng.Uniform(0.3, 0.8);
    plate_pos[1] = rng.Uniform(-0.35, 0.22);
    mj_forward(m, d);
    const mjtNum* p = d->site_xpos + 3 * beacon_site;
    session.beacon_truth.emplace_back(p[0], p[1], p[2]);
    const RgbImage image = renderer->Render(scene, "top", kWidth, kHeight);
    for (int copy = 0; copy < (i == 0 ? 2 : 1); ++copy) {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%03d.png", frame++);
      report::WritePng(image, (folder / name).string());
    }
  }
  session.true_camera = SceneCamera(scene, "top", kWidth, kHeight);
  session.intrinsics = session.true_camera.intrinsics();
  session.beacon_height_m = session.beacon_truth[0].z();
  return session;
}

/// The tabletop scene's corner tags (assets/mjcf/tabletop.xml): 6 cm squares whose black
/// border is 4.8 cm, on the table top.
std::vector<camera::TableTag> CornerTags() {
  const double yaw = 0.0;
  return {{0, {0.95, 0.55, 0.0005}, 0.048, yaw},
          {1, {0.95, -0.55, 0.0005}, 0.048, yaw},
          {2, {0.05, -0.55, 0.0005}, 0.048, yaw},
          {3, {0.05, 0.55, 0.0005}, 0.048, yaw}};
}

/// What a teacher does before confirming a pose: waits until the beacon reads from its new
/// place. The pseudo-terminal delivers lines in order, so once one reading from there has
/// arrived, no reading from the old place is still in flight to be averaged into this pose
/// (under load the hub's reader can lag by more than the collector's first drain).
void WaitUntilTheBeaconReadsFrom(uwb::BeaconHub& beacons, const Eigen::Vector3d& expected_uwb_m) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    for (const devices::BeaconSample& sample : beacons.Poll()) {
      // +-2 cm of noise on x and y: within 3 cm of the new place, and the places are further
      // apart than 6 cm (checked below), so this reading cannot come from the old one.
      if ((sample.position_uwb_m - expected_uwb_m).norm() < 0.03) return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ADD_FAILURE() << "the beacon never read from its new place";
}

class DeviceCalibrationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/recon_devcal_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(DeviceCalibrationTest, RecoversTheHiddenUwbFrameFromAnImageSequenceAndASerialBeacon) {
  const RenderedSession session = Render(dir_);
  for (int i = 1; i < kPoses; ++i) {  // so a reading tells the new place from the old one
    ASSERT_GT((session.beacon_truth[i] - session.beacon_truth[i - 1]).norm(), 0.06) << i;
  }
  // The installation's UWB frame: anchors placed 2 m off and turned 30 degrees.
  const calib::RigidTransform hidden{Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()).matrix(),
                                     Eigen::Vector3d(2.0, -1.0, 0.3)};
  std::atomic<int> pose{0};
  Rng noise(23);  // seed 23: +-2 cm of UWB noise per update
  uwb::FakeDwm1001::Options tag;
  tag.period_ms = 20;
  tag.node_id = 0xDECA000000000A01ull;
  tag.next_reading = [&] {
    const Eigen::Vector3d p = hidden.Apply(session.beacon_truth[pose.load()]);
    uwb::UwbReading r;
    r.has_position = true;
    r.x_m = p.x() + noise.Uniform(-0.02, 0.02);
    r.y_m = p.y() + noise.Uniform(-0.02, 0.02);
    r.z_m = p.z();
    r.quality = 95;
    return r;
  };
  uwb::FakeDwm1001 fake(tag);
  uwb::BeaconHubOptions hub_options;
  hub_options.ports = {fake.port()};
  hub_options.names = {{"DECA000000000A01", "plate"}};
  uwb::BeaconHub beacons(hub_options);
  camera::ImageSequenceCamera camera(dir_.string());
  devices::SteadyClock clock;

  DeviceCalibrationOptions options;
  options.points = kPoses;
  options.pose.frames = 1;
  options.pose.max_frames = 1;
  options.pose.beacon = "plate";
  options.beacon_tag = {0.044 * 0.8, session.beacon_height_m};
  std::vector<int> asked;
  const DeviceCalibrationResult result = RunDeviceCalibration(
      camera, session.intrinsics, CornerTags(), beacons, clock, options, [&](int index, int total) {
        asked.push_back(index);
        EXPECT_EQ(total, kPoses);
        pose = index;  // the teacher moves the beacon
        WaitUntilTheBeaconReadsFrom(beacons, hidden.Apply(session.beacon_truth[index]));
      });
  EXPECT_EQ(asked, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(result.camera_pose.used_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_LT(result.camera_pose.reprojection_rms_px, 1.0);
  EXPECT_LT((result.camera_pose.camera.position_table_m() - session.true_camera.position_table_m())
                .norm(),
            0.01);
  ASSERT_EQ(result.poses.size(), static_cast<size_t>(kPoses));
  for (int i = 0; i < kPoses; ++i) {
    EXPECT_LT((result.poses[i].point.tag_m - session.beacon_truth[i]).head<2>().norm(), 0.01)
        << "pose " << i;
    EXPECT_EQ(result.poses[i].uwb_samples, options.pose.uwb_samples);
  }
  EXPECT_TRUE(result.report.passed) << result.report.Summary();
  EXPECT_LT(result.report.rmse_m, 0.02);
  for (const Eigen::Vector3d& p : session.beacon_truth) {
    EXPECT_LT((result.report.transform.Apply(hidden.Apply(p)) - p).head<2>().norm(), 0.02);
  }
}

TEST_F(DeviceCalibrationTest, AnUnpluggedBeaconNamesThePoseAndTheBeacons) {
  const RenderedSession session = Render(dir_);
  uwb::FakeDwm1001::Options tag;
  tag.period_ms = 20;
  tag.next_reading = [] {
    uwb::UwbReading r;
    r.has_position = true;
    return r;
  };
  uwb::FakeDwm1001 fake(tag);
  uwb::BeaconHubOptions hub_options;
  hub_options.ports = {fake.port()};
  uwb::BeaconHub beacons(hub_options);
  camera::ImageSequenceCamera camera(dir_.string());
  devices::SteadyClock clock;
  DeviceCalibrationOptions options;
  options.points = kPoses;
  options.pose.frames = options.pose.max_frames = 1;
  options.pose.uwb_timeout_s = 0.5;
  options.beacon_tag = {0.044 * 0.8, session.beacon_height_m};
  EXPECT_THAT(
      [&] {
        RunDeviceCalibration(camera, session.intrinsics, CornerTags(), beacons, clock, options,
                             [&](int index, int) {
                               if (index == 2) fake.Unplug();
                             });
      },
      ::testing::ThrowsMessage<UserError>(
          AllOf(HasSubstr("calibration pose 3"), HasSubstr(fake.port()))));
}

TEST_F(DeviceCalibrationTest, ABeaconTagThatIsAlsoATableTagIsRefused) {
  DeviceCalibrationOptions options;
  options.pose.beacon_tag_id = 2;
  uwb::FakeDwm1001 fake({});
  uwb::BeaconHubOptions hub_options;
  hub_options.ports = {fake.port()};
  uwb::BeaconHub beacons(hub_options);
  const RenderedSession session = Render(dir_);
  camera::ImageSequenceCamera camera(dir_.string());
  devices::SteadyClock clock;
  EXPECT_THAT(
      [&] {
        RunDeviceCalibration(camera, session.intrinsics, CornerTags(), beacons, clock, options, {});
      },
      ::testing::ThrowsMessage<UserError>(HasSubstr("tag 2 is both a table tag")));
}

}  // namespace
}  // namespace recon::cell
