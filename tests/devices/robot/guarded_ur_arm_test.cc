// The safety envelope in front of the UR5 driver, against the fake UR controller over loopback
// TCP (RTDE + script port): a policy that outputs garbage at 10 Hz, a stalled control loop, the
// e-stop. What reaches the controller is read back from the controller itself.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "devices/robot/fake_ur_controller.h"
#include "devices/robot/ur_arm.h"
#include "engine/core/rng.h"
#include "engine/safety/arm_watchdog.h"
#include "engine/safety/guarded_arm.h"
#include "engine/safety/safety_envelope.h"
#include "tests/safety/garbage_commands.h"

namespace recon::robot {
namespace {

UrArm::Options ArmOptions(const FakeUrController& controller) {
  UrArm::Options options;
  options.host = "127.0.0.1";
  options.rtde_port = controller.rtde_port();
  options.script_port = controller.script_port();
  return options;
}

void Sleep(double seconds) { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }

TEST(GuardedUrArmTest, AGarbagePolicyNeverReachesTheControllerUnfiltered) {
  FakeUrController controller;
  UrArm ur(ArmOptions(controller));
  devices::SteadyClock clock;
  const safety::SafetyLimits limits;
  safety::GuardedArm arm(ur, limits, clock);
  safety::ArmWatchdog watchdog(arm);
  safety::SafetyEnvelope envelope(limits);
  Rng rng(8);  // seed 8: 30 commands (3 s at 10 Hz) of NaN, huge and plain values
  double fastest_sent = 0, lowest_tool = 1e9;
  for (int step = 0; step < 30; ++step) {
    arm.CommandJointVelocities(safety::testing::GarbageJointVelocities(rng, {0.15, 0.5, 1e12, 2}));
    if (auto sent = controller.last_speedj()) {
      for (double qd : sent->velocity_rad_s) {
        ASSERT_TRUE(std::isfinite(qd));
        fastest_sent = std::max(fastest_sent, std::abs(qd));
      }
    }
    lowest_tool = std::min(lowest_tool, envelope.ToolPoint(controller.q_rad()).z());
    Sleep(0.1);
  }
  EXPECT_LE(fastest_sent, limits.max_velocity_rad_s[0] + 1e-9);
  EXPECT_GT(fastest_sent, 0.0) << "the envelope let some motion through";
  for (double qd : controller.qd_rad_s()) EXPECT_LE(std::abs(qd), 1.0 + 1e-6);
  // The fake integrates with speedj's own acceleration; the floor has a lag margin of 1 cm.
  EXPECT_GE(lowest_tool, limits.tool_floor_m - 0.01);
  EXPECT_EQ(controller.safety_mode(), 1) << "no protective stop was needed";
  const safety::SafetyStats stats = arm.stats();
  EXPECT_EQ(stats.commands, 30);
  EXPECT_GT(stats.non_finite, 0);
  EXPECT_GT(stats.velocity, 0);
  EXPECT_EQ(controller.malformed_lines(), 0) << "every line sent was valid URScript";
}

TEST(GuardedUrArmTest, TheWatchdogStopsTheRobotWhenTheControlLoopStalls) {
  FakeUrController controller;
  UrArm::Options options = ArmOptions(controller);
  options.speedj_time_s = 5.0;  // a controller that would keep moving on its own for 5 s
  UrArm ur(options);
  devices::SteadyClock clock;
  safety::GuardedArm arm(ur, safety::SafetyLimits{}, clock);
  safety::ArmWatchdog watchdog(arm);
  arm.CommandJointVelocities({0.3, 0, 0, 0, 0, 0});
  // Polled, not timed: the watchdog must stop the robot well before speedj's 5 s run out.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (watchdog.trips() == 0 && std::chrono::steady_clock::now() < until) Sleep(0.01);
  ASSERT_EQ(watchdog.trips(), 1);
  Sleep(0.5);  // stopj decelerates at 2 rad/s^2 from at most 0.3 rad/s
  EXPECT_LT(std::abs(controller.qd_rad_s()[0]), 1e-6);
  const double q_after = controller.q_rad()[0];
  Sleep(0.3);
  EXPECT_NEAR(controller.q_rad()[0], q_after, 1e-6) << "still moving after the watchdog";
}

TEST(GuardedUrArmTest, TheEmergencyStopHaltsTheRobotAndRefusesMotion) {
  FakeUrController controller;
  UrArm ur(ArmOptions(controller));
  devices::SteadyClock clock;
  safety::GuardedArm arm(ur, safety::SafetyLimits{}, clock);
  for (int i = 0; i < 5; ++i) {
    arm.CommandJointVelocities({0.0, 0.3, 0, 0, 0, 0});
    Sleep(0.05);
  }
  const auto before = controller.last_speedj();
  ASSERT_TRUE(before.has_value());
  arm.EngageEmergencyStop("test");
  const int64_t commands = controller.commands_received();
  for (int i = 0; i < 5; ++i) {
    // Slower than before, so a speedj that got through would differ from the last one.
    arm.CommandJointVelocities({0.0, 0.2, 0, 0, 0, 0});
    arm.CommandGripper(true);
    Sleep(0.05);
  }
  Sleep(0.3);
  EXPECT_LT(std::abs(controller.qd_rad_s()[1]), 1e-6);
  EXPECT_FALSE(controller.tool_output(0)) << "the gripper was commanded during the e-stop";
  // Only stops went out after the e-stop (one per refused command), no speedj.
  const auto last = controller.last_speedj();
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->velocity_rad_s, before->velocity_rad_s) << "a speedj was sent after the e-stop";
  EXPECT_GT(controller.commands_received(), commands);
  EXPECT_EQ(arm.stats().emergency_stop, 5);
}

}  // namespace
}  // namespace recon::robot
