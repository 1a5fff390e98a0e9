// `recon robot status` as a user runs it: against the built-in fake controller, against a port
// where nothing answers, and with wrong arguments.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "devices/robot/fake_ur_controller.h"
#include "devices/robot/tcp_socket.h"
#include "tests/app/run_recon.h"

namespace recon {
namespace {

using ::testing::HasSubstr;

/// The last line of the output that is a JSON object.
nlohmann::json LastJson(const std::string& output) {
  std::istringstream lines(output);
  std::string line;
  nlohmann::json last;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] == '{') last = nlohmann::json::parse(line);
  }
  return last;
}

TEST(RobotCliTest, StatusAgainstTheBuiltInFakeReportsModesJointsAndRate) {
  const testing::CommandResult r = testing::RunRecon("robot status --fake --seconds 0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json status = LastJson(r.output);
  ASSERT_TRUE(status.is_object()) << r.output;
  EXPECT_EQ(status["host"], "127.0.0.1");
  EXPECT_TRUE(status["fake"].get<bool>());
  EXPECT_EQ(status["controller_version"], "5.11.0.108");
  EXPECT_EQ(status["robot_mode"].get<int>(), 7);
  EXPECT_EQ(status["robot_mode_name"], "RUNNING");
  EXPECT_EQ(status["safety_mode"].get<int>(), 1);
  EXPECT_EQ(status["safety_mode_name"], "NORMAL");
  ASSERT_EQ(status["q_deg"].size(), 6u);
  EXPECT_NEAR(status["q_deg"][0].get<double>(), 180.0, 1e-6) << "the fake's home, base at pi";
  ASSERT_EQ(status["qd_rad_s"].size(), 6u);
  EXPECT_EQ(status["qd_rad_s"][0].get<double>(), 0.0);
  EXPECT_TRUE(status["script_port_open"].get<bool>());
  EXPECT_GT(status["packets"].get<int>(), 10) << "a live stream, not a timing check";
  EXPECT_GT(status["rate_hz"].get<double>(), 0.0);
  EXPECT_EQ(status["requested_rate_hz"].get<double>(), 125.0);
}

TEST(RobotCliTest, StatusTableAgainstARunningFakeOnItsPorts) {
  robot::FakeUrController fake;
  const testing::CommandResult r = testing::RunRecon(
      "robot status --host 127.0.0.1 --rtde-port " + std::to_string(fake.rtde_port()) +
      " --script-port " + std::to_string(fake.script_port()) + " --seconds 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("UR controller 5.11.0.108 at 127.0.0.1"));
  EXPECT_THAT(r.output, HasSubstr("robot mode   RUNNING (7)"));
  EXPECT_THAT(r.output, HasSubstr("safety mode  NORMAL (1)"));
  EXPECT_THAT(r.output, HasSubstr("shoulder"));
  EXPECT_THAT(r.output, HasSubstr("accepts connections"));
  EXPECT_EQ(fake.rtde_clients(), 1);
  EXPECT_EQ(fake.commands_received() + fake.malformed_lines(), 0) << "status never sends script";
}

TEST(RobotCliTest, NothingAnsweringIsExitTwoNamingHostAndPort) {
  int free_port;
  {
    robot::TcpListener probe(0);
    free_port = probe.port();
  }
  const testing::CommandResult r =
      testing::RunRecon("robot status --host 127.0.0.1 --rtde-port " + std::to_string(free_port));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("127.0.0.1:" + std::to_string(free_port)));
  EXPECT_THAT(r.output, HasSubstr("refused"));
}

TEST(RobotCliTest, WrongArgumentsAreUsageErrors) {
  testing::CommandResult r = testing::RunRecon("robot status");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--host"));
  r = testing::RunRecon("robot status --host 127.0.0.1 --rtde-port 70000");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--rtde-port"));
  r = testing::RunRecon("robot status --fake --seconds -1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = testing::RunRecon("robot");
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace recon
