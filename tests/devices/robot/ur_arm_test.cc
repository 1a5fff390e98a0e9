// UrArm driving FakeUrController over loopback TCP, as the workflow drives a real UR5: velocity
// commands move the joints by about qd * t, stopj and the speedj timeout halt them, the gripper
// output follows, and a robot that is stopped or gone is an error rather than silence.

#include "devices/robot/ur_arm.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

#include "devices/robot/fake_ur_controller.h"
#include "devices/robot/ur_modes.h"
#include "engine/core/error.h"

namespace recon::robot {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

UrArm::Options ArmLoopback(const FakeUrController& fake) {
  UrArm::Options options;
  options.host = "127.0.0.1";
  options.rtde_port = fake.rtde_port();
  options.script_port = fake.script_port();
  return options;
}

/// Polls `done` for up to `seconds`; the fake runs on its own threads.
bool WaitUntil(const std::function<bool()>& done, double seconds = 3.0) {
  const auto until = Clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    if (Clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

bool AtRest(const FakeUrController& fake) {
  for (double v : fake.qd_rad_s()) {
    if (v != 0.0) return false;
  }
  return true;
}

TEST(UrArmTest, StreamingVelocitiesMovesTheJointsByAboutVelocityTimesTime) {
  FakeUrController fake;
  UrArm arm(ArmLoopback(fake));
  EXPECT_THAT(arm.Describe(), HasSubstr("UR5 at 127.0.0.1"));
  EXPECT_THAT(arm.Describe(), HasSubstr("5.11.0.108"));
  const devices::JointState start = arm.State();
  const std::array<double, 6> home = FakeUrController::Options{}.home_q_rad;
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(start.position_rad[i], home[i], 1e-12);

  const std::array<double, 6> qd = {0.2, -0.1, 0, 0, 0.3, 0};
  const auto began = Clock::now();
  while (Clock::now() - began < std::chrono::seconds(1)) {
    arm.CommandJointVelocities(qd);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double commanded_s = std::chrono::duration<double>(Clock::now() - began).count();
  ASSERT_TRUE(WaitUntil([&] { return AtRest(fake); })) << "the speedj timeout stops the arm";
  const std::array<double, 6> q = fake.q_rad();
  for (size_t i = 0; i < 6; ++i) {
    // qd * t, give or take the acceleration ramps (a = 1.4 rad/s^2) and a loaded machine.
    const double expected = qd[i] * commanded_s;
    EXPECT_NEAR(q[i] - home[i], expected, 0.35 * std::abs(expected) + 0.05) << "joint " << i;
    if (qd[i] != 0) {
      EXPECT_GT((q[i] - home[i]) / qd[i], 0.5 * commanded_s) << "joint " << i;
    }
  }
  ASSERT_TRUE(arm.rtde().WaitForData(1.0, arm.rtde().packets_received()));
  const devices::JointState end = arm.State();
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(end.position_rad[i], q[i], 1e-9);
  EXPECT_GT(end.timestamp_s, start.timestamp_s);
  const std::optional<UrScriptCommand> last = fake.last_speedj();
  ASSERT_TRUE(last);
  EXPECT_DOUBLE_EQ(last->acceleration_rad_s2, 1.4);
  EXPECT_DOUBLE_EQ(last->time_s, 0.1);
  EXPECT_DOUBLE_EQ(last->velocity_rad_s[4], 0.3);
  EXPECT_EQ(fake.malformed_lines(), 0);
}

TEST(UrArmTest, StopHaltsALongCommandAndTheTimeoutHaltsAnAbandonedOne) {
  FakeUrController fake;
  UrArm::Options options = ArmLoopback(fake);
  options.speedj_time_s = 30;  // only stopj can end this one early
  {
    UrArm arm(options);
    arm.CommandJointVelocities({0, 0, 0, 0, 0, 0.5});
    ASSERT_TRUE(WaitUntil([&] { return fake.qd_rad_s()[5] > 0.4; }));
    arm.Stop();
    ASSERT_TRUE(WaitUntil([&] { return AtRest(fake); }, 2.0)) << "stopj at 2 rad/s^2: 0.25 s";
    const double stopped_at = fake.q_rad()[5];
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(fake.q_rad()[5], stopped_at);
  }
  // One command with t = 0.1 s and then nothing, as from a crashed policy: the controller stops.
  options.speedj_time_s = 0.1;
  UrArm arm(options);
  const double before = fake.q_rad()[0];
  arm.CommandJointVelocities({0.5, 0, 0, 0, 0, 0});
  ASSERT_TRUE(WaitUntil([&] { return fake.qd_rad_s()[0] > 0; }));
  ASSERT_TRUE(WaitUntil([&] { return AtRest(fake); }, 2.0));
  // Up for at most 0.1 s (at 1.4 rad/s^2 that is 0.14 rad/s), then down: a few centiradians.
  EXPECT_GT(fake.q_rad()[0], before);
  EXPECT_LT(fake.q_rad()[0] - before, 0.05);
}

TEST(UrArmTest, GripperIsToolOutputZeroAndNaNIsNeverSent) {
  FakeUrController fake;
  UrArm arm(ArmLoopback(fake));
  arm.CommandGripper(true);
  EXPECT_TRUE(WaitUntil([&] { return fake.tool_output(0); }));
  EXPECT_EQ(arm.State().gripper_opening, 0.0);
  arm.CommandGripper(false);
  EXPECT_TRUE(WaitUntil([&] { return !fake.tool_output(0); }));
  EXPECT_EQ(arm.State().gripper_opening, 1.0);

  const int64_t before = fake.commands_received();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(arm.CommandJointVelocities({0, nan, 0, 0, 0, 0}), UserError);
  // Too fast is clamped to the UR5's pi rad/s, not refused.
  arm.CommandJointVelocities({10, 0, 0, 0, 0, 0});
  ASSERT_TRUE(WaitUntil([&] { return fake.commands_received() == before + 1; }));
  EXPECT_NEAR(fake.last_speedj()->velocity_rad_s[0], 3.14159265358979, 1e-9);
  EXPECT_EQ(fake.malformed_lines(), 0);
}

TEST(UrArmTest, AProtectiveStopAtAJointLimitRefusesFurtherMotion) {
  FakeUrController fake;
  std::array<double, 6> near_limit = FakeUrController::Options{}.home_q_rad;
  near_limit[5] = 2 * 3.14159265358979 - 0.01;
  fake.Teleport(near_limit);
  UrArm::Options options = ArmLoopback(fake);
  options.speedj_time_s = 1.0;
  UrArm arm(options);
  arm.CommandJointVelocities({0, 0, 0, 0, 0, 0.5});
  ASSERT_TRUE(WaitUntil([&] { return fake.safety_mode() == kSafetyModeProtectiveStop; }));
  EXPECT_TRUE(AtRest(fake));
  ASSERT_TRUE(
      WaitUntil([&] { return arm.rtde().Latest()->safety_mode == kSafetyModeProtectiveStop; }));
  try {
    arm.CommandJointVelocities({0, 0, 0, 0, 0, -0.1});
    FAIL() << "a command was sent to a protectively stopped robot";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("PROTECTIVE_STOP"));
  }
  fake.ClearProtectiveStop();
  ASSERT_TRUE(WaitUntil([&] { return arm.rtde().Latest()->safety_mode == kSafetyModeNormal; }));
  arm.CommandJointVelocities({0, 0, 0, 0, 0, -0.1});
}

TEST(UrArmTest, ARobotThatGoesAwayIsAnErrorNamingIt) {
  FakeUrController fake;
  UrArm arm(ArmLoopback(fake));
  fake.Stop();
  ASSERT_TRUE(WaitUntil([&] { return !arm.rtde().connected(); }));
  try {
    arm.State();
    FAIL() << "a state from a robot that is gone";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("127.0.0.1:" + std::to_string(fake.rtde_port())));
  }
  EXPECT_THROW(arm.CommandJointVelocities({}), UserError);
  EXPECT_THROW(arm.Stop(), UserError);
  // And one that never was.
  UrArm::Options options = ArmLoopback(fake);
  options.timeout_s = 0.5;
  EXPECT_THROW(UrArm{options}, UserError);
}

}  // namespace
}  // namespace recon::robot
