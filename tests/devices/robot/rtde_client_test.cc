// RtdeClient against FakeUrController over real loopback TCP: the handshake, the stream, what a
// wrong name or a missing robot looks like, and a robot that goes away.

#include "devices/robot/rtde_client.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "devices/robot/fake_ur_controller.h"
#include "devices/robot/tcp_socket.h"
#include "devices/robot/ur_modes.h"
#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::robot {
namespace {

using ::testing::HasSubstr;

RtdeClient::Options ClientLoopback(const FakeUrController& fake) {
  RtdeClient::Options options;
  options.host = "127.0.0.1";
  options.port = fake.rtde_port();
  return options;
}

TEST(RtdeClientTest, HandshakesAndStreamsTheFakesState) {
  FakeUrController fake;
  ASSERT_GT(fake.rtde_port(), 0);
  ASSERT_NE(fake.rtde_port(), fake.script_port());
  RtdeClient client(ClientLoopback(fake));
  EXPECT_EQ(client.controller_version().ToString(), "5.11.0.108");
  EXPECT_GT(client.recipe().id, 0);
  EXPECT_EQ(client.recipe().types.size(), RtdeClient::DefaultOutputs().size());
  // Liveness, not timing: 50 packages prove the stream (125 Hz gives them in 0.4 s). Waited for
  // with a deadline far beyond that, so a loaded machine that schedules the fake late does not
  // fail the test; a stream that stops does.
  const auto start = std::chrono::steady_clock::now();
  while (client.packets_received() < 50 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(30)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(client.connected()) << client.last_error();
  EXPECT_GE(client.packets_received(), 50);
  const double waited_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%lld RTDE packages in %.2f s over loopback, %.1f Hz measured\n",
              static_cast<long long>(client.packets_received()), waited_s,
              client.measured_rate_hz());
  EXPECT_GT(client.measured_rate_hz(), 0);
  EXPECT_EQ(client.protocol_errors(), 0);
  const std::optional<RtdeState> state = client.Latest();
  ASSERT_TRUE(state);
  EXPECT_EQ(state->robot_mode, kRobotModeRunning);
  EXPECT_EQ(state->safety_mode, kSafetyModeNormal);
  const std::array<double, 6> home = FakeUrController::Options{}.home_q_rad;
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(state->actual_q_rad[i], home[i], 1e-12);
  EXPECT_GT(state->controller_time_s, 0);
  EXPECT_NE(state->actual_tcp_pose[2], 0.0) << "a TCP pose from the kinematics";
  EXPECT_LE(state->received_s, SteadySeconds());
  EXPECT_GE(fake.data_packets_sent(), client.packets_received());
}

TEST(RtdeClientTest, SequentialClientsEachGetTheirOwnStream) {
  FakeUrController fake;
  for (int i = 0; i < 3; ++i) {
    RtdeClient client(ClientLoopback(fake));
    EXPECT_TRUE(client.WaitForData(2.0)) << "client " << i << ": " << client.last_error();
  }
  EXPECT_EQ(fake.rtde_clients(), 3);
}

TEST(RtdeClientTest, AnUnknownOutputIsNamedInTheError) {
  FakeUrController fake;
  RtdeClient::Options options = ClientLoopback(fake);
  options.outputs = {"timestamp", "actual_q", "actual_joint_temperaturez"};
  try {
    RtdeClient client(options);
    FAIL() << "an unknown output was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("actual_joint_temperaturez"));
    EXPECT_THAT(e.what(), HasSubstr("NOT_FOUND"));
    EXPECT_THAT(e.what(), HasSubstr("127.0.0.1:" + std::to_string(fake.rtde_port())));
  }
}

TEST(RtdeClientTest, ARefusedOrSilentPortIsAClearError) {
  int free_port;
  {
    TcpListener probe(0);  // a port that was free a moment ago and is closed now
    free_port = probe.port();
  }
  RtdeClient::Options options;
  options.host = "127.0.0.1";
  options.port = free_port;
  options.timeout_s = 0.5;
  try {
    RtdeClient client(options);
    FAIL() << "connected to a closed port";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("127.0.0.1:" + std::to_string(free_port)));
    EXPECT_THAT(e.what(), HasSubstr("refused"));
  }
  // Something listens but never answers RTDE (the wrong port, say the dashboard's).
  TcpListener silent(0);
  options.port = silent.port();
  try {
    RtdeClient client(options);
    FAIL() << "no reply was taken for one";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("no RTDE reply from 127.0.0.1:" + std::to_string(silent.port())));
  }
}

TEST(RtdeClientTest, ARobotThatGoesAwayIsDetected) {
  FakeUrController fake;
  RtdeClient client(ClientLoopback(fake));
  ASSERT_TRUE(client.WaitForData(2.0));
  fake.Stop();
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (client.connected() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_FALSE(client.connected());
  EXPECT_THAT(client.last_error(), HasSubstr("closed the RTDE connection"));
  EXPECT_THAT(client.last_error(), HasSubstr(client.where()));
  EXPECT_FALSE(client.WaitForData(0.2, client.packets_received()));
}

}  // namespace
}  // namespace recon::robot
