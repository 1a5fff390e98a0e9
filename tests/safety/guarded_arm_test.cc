// GuardedArm over arms: a recording arm for the exact calls, the simulated UR5 (MuJoCo) for the
// physical outcome of a policy that outputs garbage. The same decorator over the real UR5 driver
// and the fake UR controller is tested in tests/devices/robot/guarded_ur_arm_test.cc.

#include "engine/safety/guarded_arm.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/safety/arm_watchdog.h"
#include "engine/worlds/simulated_arm.h"
#include "engine/worlds/ur5_arm.h"
#include "tests/safety/garbage_commands.h"
#include "tests/worlds/ur5_test_scene.h"

namespace recon::safety {
namespace {

/// An arm that records what it was told and stays at home.
class RecordingArm final : public devices::Arm {
 public:
  devices::JointState State() const override {
    devices::JointState s;
    s.position_rad = worlds::Ur5Arm::kHome;
    return s;
  }
  void CommandJointVelocities(const std::array<double, 6>& v) override { commands.push_back(v); }
  void CommandGripper(bool close) override { gripper.push_back(close); }
  void Stop() override { ++stops; }
  std::string Describe() const override { return "recording arm"; }

  std::vector<JointVector> commands;
  std::vector<bool> gripper;
  int stops = 0;
};

TEST(GuardedArmTest, PassesJudgedCommandsAndCountsWhatItChanged) {
  RecordingArm inner;
  devices::ManualClock clock;
  GuardedArm arm(inner, SafetyLimits{}, clock);
  arm.CommandJointVelocities({0.3, 0, 0, 0, 0, 0});
  clock.Advance(0.1);
  arm.CommandJointVelocities({50, 0, 0, 0, 0, 0});  // velocity and acceleration
  clock.Advance(0.1);
  arm.CommandJointVelocities({std::nan(""), 0, 0, 0, 0, 0});
  ASSERT_EQ(inner.commands.size(), 2u);
  EXPECT_DOUBLE_EQ(inner.commands[0][0], 0.3);
  EXPECT_NEAR(inner.commands[1][0], 0.8, 1e-12);  // 0.3 + 5 rad/s^2 x 0.1 s
  EXPECT_EQ(inner.stops, 1);                      // the NaN became a stop
  const SafetyStats stats = arm.stats();
  EXPECT_EQ(stats.commands, 3);
  EXPECT_EQ(stats.changed, 2);
  EXPECT_EQ(stats.velocity, 1);
  EXPECT_EQ(stats.acceleration, 1);
  EXPECT_EQ(stats.non_finite, 1);
  EXPECT_EQ(arm.last_decision().reasons, kNonFinite);
  EXPECT_NE(arm.Describe().find("recording arm, safety envelope 1 rad/s"), std::string::npos)
      << arm.Describe();
}

TEST(GuardedArmTest, WatchdogStopsTheArmWhenCommandsStop) {
  RecordingArm inner;
  devices::ManualClock clock;
  GuardedArm arm(inner, SafetyLimits{}, clock);
  EXPECT_FALSE(arm.CheckWatchdog());  // nothing commanded yet
  arm.CommandJointVelocities({0.2, 0, 0, 0, 0, 0});
  clock.Advance(0.15);
  EXPECT_FALSE(arm.CheckWatchdog());
  EXPECT_EQ(inner.stops, 0);
  clock.Advance(0.1);  // 250 ms since the command
  EXPECT_TRUE(arm.CheckWatchdog());
  EXPECT_EQ(inner.stops, 1);
  EXPECT_FALSE(arm.CheckWatchdog());  // already stopped: once is enough
  EXPECT_EQ(arm.stats().watchdog, 1);
  // Commands resume from rest, under the acceleration limit.
  arm.CommandJointVelocities({0.9, 0, 0, 0, 0, 0});
  EXPECT_NEAR(inner.commands.back()[0], 0.5, 1e-12);
}

TEST(GuardedArmTest, EmergencyStopRefusesMotionUntilReleased) {
  RecordingArm inner;
  devices::ManualClock clock;
  GuardedArm arm(inner, SafetyLimits{}, clock);
  arm.CommandJointVelocities({0.2, 0, 0, 0, 0, 0});
  arm.EngageEmergencyStop("button");
  EXPECT_TRUE(arm.emergency_stopped());
  EXPECT_EQ(arm.emergency_stop_reason(), "button");
  const size_t before = inner.commands.size();
  const int stops = inner.stops;
  clock.Advance(0.1);
  arm.CommandJointVelocities({0.2, 0, 0, 0, 0, 0});
  arm.CommandGripper(true);
  EXPECT_EQ(inner.commands.size(), before);
  EXPECT_GT(inner.stops, stops);
  EXPECT_TRUE(inner.gripper.empty());
  EXPECT_EQ(arm.last_decision().reasons, kEmergencyStop);
  arm.ReleaseEmergencyStop();
  clock.Advance(0.1);
  arm.CommandJointVelocities({0.2, 0, 0, 0, 0, 0});
  EXPECT_EQ(inner.commands.size(), before + 1);
}

// A simulated world commands once a control period, but its clock's readings carry rounding:
// 0.7 - 0.6 is not 0.1. With the period given, the acceleration rule is applied over exactly one
// period, so a run does not depend in the last bit on how long the clock had run before it.
TEST(GuardedArmTest, ACommandPeriodJudgesWholePeriodsNotClockDifferences) {
  RecordingArm by_clock, by_period;
  devices::ManualClock clock;
  GuardedArm a(by_clock, SafetyLimits{}, clock), b(by_period, SafetyLimits{}, clock);
  b.SetCommandPeriod(0.1);
  clock.Set(0.6);
  a.CommandJointVelocities({0, 0, 0, 0, 0, 0});
  b.CommandJointVelocities({0, 0, 0, 0, 0, 0});
  clock.Set(0.7);
  ASSERT_NE(0.7 - 0.6, 0.1);
  a.CommandJointVelocities({0.9, 0, 0, 0, 0, 0});
  b.CommandJointVelocities({0.9, 0, 0, 0, 0, 0});
  EXPECT_LT(by_clock.commands.back()[0], 0.5);  // 5 rad/s^2 x 0.0999...
  EXPECT_EQ(by_period.commands.back()[0], 5 * 0.1);
  EXPECT_THROW(b.SetCommandPeriod(0), UserError);
  EXPECT_THROW(b.SetCommandPeriod(std::nan("")), UserError);
}

// After a stop (Stop(), the watchdog, an e-stop's release) the arm is at rest, and the next
// command may ask for one period's (or lookahead's) acceleration only, however long ago the last
// command was.
TEST(GuardedArmTest, AfterAStopTheNextCommandStartsFromRest) {
  RecordingArm inner;
  devices::ManualClock clock;
  GuardedArm arm(inner, SafetyLimits{}, clock);
  arm.SetCommandPeriod(0.1);
  arm.CommandJointVelocities({0.4, 0, 0, 0, 0, 0});
  arm.Stop();
  clock.Advance(5.0);
  arm.CommandJointVelocities({0.9, 0, 0, 0, 0, 0});
  EXPECT_EQ(inner.commands.back()[0], 0.5);
}

TEST(GuardedArmTest, WatchdogThreadStopsAStalledControlLoop) {
  RecordingArm inner;
  devices::SteadyClock clock;
  GuardedArm arm(inner, SafetyLimits{}, clock);
  ArmWatchdog watchdog(arm, 5);
  arm.CommandJointVelocities({0.2, 0, 0, 0, 0, 0});
  // The control loop stalls; the watchdog must stop the arm on its own. Polled (no timing
  // assert): it has up to 5 s, and is expected within about 0.2 s.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (watchdog.trips() == 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(watchdog.trips(), 1);
  EXPECT_EQ(inner.stops, 1);
}

TEST(GuardedArmTest, ToolPointMatchesTheSimulatedGripper) {
  worlds::MujocoModel scene = worlds::testing::MakeArmTestScene();
  worlds::Ur5Arm ur5(scene);
  SafetyEnvelope envelope{SafetyLimits{}};
  Rng rng(5);  // seed 5: 30 random configurations
  for (int trial = 0; trial < 30; ++trial) {
    worlds::Ur5Joints q;
    for (double& v : q) v = rng.Uniform(-3.0, 3.0);
    ur5.Reset(q);
    EXPECT_LT((envelope.ToolPoint(q) - ur5.GripPosition()).norm(), 5e-4);
  }
}

TEST(GuardedArmTest, ASimulatedUr5DrivenByGarbageStaysInsideTheEnvelope) {
  worlds::MujocoModel scene = worlds::testing::MakeArmTestScene();
  worlds::Ur5Arm ur5(scene);
  ur5.Reset(worlds::Ur5Arm::kHome);
  devices::ManualClock clock;
  worlds::SimulatedArm simulated(ur5, clock);
  const SafetyLimits limits;
  GuardedArm arm(simulated, limits, clock);
  Rng rng(99);  // seed 99: 300 control steps (30 s) of a policy gone wrong
  double lowest_z = 1e9, fastest = 0;
  for (int step = 0; step < 300; ++step) {
    arm.CommandJointVelocities(testing::GarbageJointVelocities(rng, {0.1, 0.4, 1e9, 2}));
    simulated.CheckWatchdog();
    ur5.Step(0.1);
    clock.Advance(0.1);
    lowest_z = std::min(lowest_z, ur5.GripPosition().z());
    for (double qd : ur5.JointVelocities()) fastest = std::max(fastest, std::abs(qd));
  }
  // The servo tracks the commanded velocity with a small lag, hence the margins.
  EXPECT_GE(lowest_z, limits.tool_floor_m - 0.005);
  EXPECT_LE(fastest, limits.max_velocity_rad_s[0] * 1.2);
  EXPECT_GT(arm.stats().non_finite, 0);
  EXPECT_GT(arm.stats().velocity, 0);
}

}  // namespace
}  // namespace recon::safety
