// Device discovery over a device folder like /dev: symlinks to fake DWM1001 pseudo-terminals
// (one answering, one silent), a file that is no camera, a FIFO carrying joystick events, and a
// fake UR controller on loopback TCP.

#include "devices/discovery/device_discovery.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "devices/robot/fake_ur_controller.h"
#include "devices/uwb/fake_dwm1001.h"
#include "devices/uwb/uwb_reading.h"

namespace recon::discovery {
namespace {

namespace fs = std::filesystem;

class DiscoveryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/recon_discovery_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

const FoundDevice* Find(const std::vector<FoundDevice>& found, const std::string& path) {
  for (const auto& d : found) {
    if (d.path == path) return &d;
  }
  return nullptr;
}

TEST_F(DiscoveryTest, ProbesBeaconsCamerasGamepadsAndRobots) {
  uwb::FakeDwm1001::Options tag;
  tag.node_id = 0xDECA0000000012ABull;
  tag.next_reading = [] {
    uwb::UwbReading r;
    r.has_position = true;
    r.x_m = 1.0;
    r.quality = 90;
    return r;
  };
  uwb::FakeDwm1001 beacon(tag);
  // A second pseudo-terminal with nothing behind it: some other USB serial gadget.
  const int silent = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(silent, 0);
  ASSERT_EQ(grantpt(silent), 0);
  ASSERT_EQ(unlockpt(silent), 0);
  fs::create_symlink(beacon.port(), dir_ / "ttyACM0");
  fs::create_symlink(ptsname(silent), dir_ / "ttyACM1");
  fs::create_directories(dir_ / "serial" / "by-id");
  fs::create_symlink(dir_ / "ttyACM0", dir_ / "serial" / "by-id" / "usb-SEGGER_J-Link_760012345");
  std::ofstream(dir_ / "video0") << "not a camera";
  fs::create_directories(dir_ / "input");
  ASSERT_EQ(mkfifo((dir_ / "input" / "js0").c_str(), 0600), 0);
  robot::FakeUrController controller;

  DiscoveryOptions options;
  options.dev_dir = dir_.string();
  options.serial_timeout_ms = 700;
  options.robot_hosts = {"127.0.0.1:" + std::to_string(controller.rtde_port()),
                         "127.0.0.1:1"};  // nothing listens on port 1
  const std::vector<FoundDevice> found = DiscoverDevices(options);
  ASSERT_EQ(found.size(), 6u);

  const FoundDevice* dwm = Find(found, (dir_ / "ttyACM0").string());
  ASSERT_NE(dwm, nullptr);
  EXPECT_EQ(dwm->kind, DeviceKind::kBeacon);
  EXPECT_TRUE(dwm->usable) << dwm->detail;
  EXPECT_EQ(dwm->identity, "DWM1001 node DECA0000000012AB");
  EXPECT_NE(dwm->detail.find("12AB"), std::string::npos) << dwm->detail;

  const FoundDevice* other = Find(found, (dir_ / "ttyACM1").string());
  ASSERT_NE(other, nullptr);
  EXPECT_FALSE(other->usable);
  EXPECT_NE(other->detail.find("ttyACM1"), std::string::npos) << other->detail;

  const FoundDevice* camera = Find(found, (dir_ / "video0").string());
  ASSERT_NE(camera, nullptr);
  EXPECT_EQ(camera->kind, DeviceKind::kCamera);
  EXPECT_FALSE(camera->usable);
  EXPECT_NE(camera->detail.find("video0"), std::string::npos) << camera->detail;

  const FoundDevice* pad = Find(found, (dir_ / "input" / "js0").string());
  ASSERT_NE(pad, nullptr);
  EXPECT_EQ(pad->kind, DeviceKind::kGamepad);
  EXPECT_TRUE(pad->usable) << pad->detail;

  const FoundDevice* ur = Find(found, options.robot_hosts[0]);
  ASSERT_NE(ur, nullptr);
  EXPECT_EQ(ur->kind, DeviceKind::kRobot);
  EXPECT_TRUE(ur->usable) << ur->detail;
  EXPECT_EQ(ur->identity.rfind("UR controller ", 0), 0u) << ur->identity;
  const FoundDevice* nobody = Find(found, "127.0.0.1:1");
  ASSERT_NE(nobody, nullptr);
  EXPECT_FALSE(nobody->usable);
  EXPECT_NE(nobody->detail.find("127.0.0.1:1"), std::string::npos) << nobody->detail;
  close(silent);
}

TEST_F(DiscoveryTest, WithoutProbingListsFilesAndTheByIdName) {
  std::ofstream(dir_ / "ttyUSB3") << "";
  fs::create_directories(dir_ / "serial" / "by-id");
  fs::create_symlink(dir_ / "ttyUSB3", dir_ / "serial" / "by-id" / "usb-FTDI_adapter-if00");
  std::ofstream(dir_ / "video2") << "";
  std::ofstream(dir_ / "tty0") << "";  // a console, not a USB serial port
  DiscoveryOptions options;
  options.dev_dir = dir_.string();
  options.probe = false;
  const std::vector<FoundDevice> found = DiscoverDevices(options);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].kind, DeviceKind::kBeacon);
  EXPECT_EQ(found[0].identity, "usb-FTDI_adapter-if00");
  EXPECT_TRUE(found[0].usable);
  EXPECT_EQ(found[1].kind, DeviceKind::kCamera);
  EXPECT_EQ(std::string(DeviceKindName(found[1].kind)), "camera");
}

TEST_F(DiscoveryTest, AnEmptyFolderFindsNothing) {
  DiscoveryOptions options;
  options.dev_dir = dir_.string();
  EXPECT_TRUE(DiscoverDevices(options).empty());
}

}  // namespace
}  // namespace recon::discovery
