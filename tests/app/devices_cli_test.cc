// `recon devices list` as a user runs it: a device folder holding a symlink to a fake DWM1001's
// pseudo-terminal, and a fake UR controller on loopback, found and probed by the real binary.

#include <stdlib.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "devices/robot/fake_ur_controller.h"
#include "devices/uwb/fake_dwm1001.h"
#include "tests/app/run_recon.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::RunRecon;

TEST(DevicesCliTest, ListsAndProbesABeaconAndARobot) {
  char tmpl[] = "/tmp/recon_devices_cli_XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const fs::path dir = tmpl;
  uwb::FakeDwm1001::Options tag;
  tag.node_id = 0xDECA00000000BEEFull;
  uwb::FakeDwm1001 beacon(tag);
  fs::create_symlink(beacon.port(), dir / "ttyACM0");
  robot::FakeUrController controller;
  const std::string robot = "127.0.0.1:" + std::to_string(controller.rtde_port());

  const CommandResult result =
      RunRecon("devices list --json --dev " + dir.string() + " --robot-host " + robot);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const size_t start = result.output.find('{');
  ASSERT_NE(start, std::string::npos) << result.output;
  const nlohmann::json list = nlohmann::json::parse(result.output.substr(start));
  ASSERT_EQ(list["devices"].size(), 2u) << result.output;
  EXPECT_EQ(list["devices"][0]["kind"], "beacon");
  EXPECT_EQ(list["devices"][0]["identity"], "DWM1001 node DECA00000000BEEF");
  EXPECT_TRUE(list["devices"][0]["usable"].get<bool>());
  EXPECT_EQ(list["devices"][1]["kind"], "robot");
  EXPECT_EQ(list["devices"][1]["path"], robot);
  EXPECT_TRUE(list["devices"][1]["usable"].get<bool>()) << result.output;

  const CommandResult table = RunRecon("devices list --no-probe --dev " + dir.string());
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_NE(table.output.find("ttyACM0"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("--robot-host"), std::string::npos) << table.output;
  fs::remove_all(dir);
}

TEST(DevicesCliTest, WrongArgumentsAreRefused) {
  EXPECT_EQ(RunRecon("devices list --dev /nonexistent/folder").exit_code, 2);
  EXPECT_NE(RunRecon("devices").exit_code, 0);
  EXPECT_NE(RunRecon("devices list --serial-timeout-ms -3").exit_code, 0);
}

}  // namespace
}  // namespace recon
