// SimulatedArm on the tabletop scene's UR5, physics stepped by the test as the cell would:
// state, clamping, Stop and the watchdog.

#include "engine/worlds/simulated_arm.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/worlds/scene_assets.h"

namespace recon::worlds {
namespace {

constexpr double kPeriod_s = 0.1;

class SimulatedArmTest : public ::testing::Test {
 protected:
  SimulatedArmTest() : scene_(worlds::LoadScene("tabletop")), ur5_(scene_) {
    ur5_.Reset(worlds::Ur5Arm::kHome);
  }

  // One control period as a world steps it: watchdog, physics, clock.
  void Advance(SimulatedArm& arm) {
    arm.CheckWatchdog();
    ur5_.Step(kPeriod_s);
    clock_.Advance(kPeriod_s);
  }

  worlds::MujocoModel scene_;
  worlds::Ur5Arm ur5_;
  devices::ManualClock clock_;
};

TEST_F(SimulatedArmTest, StateFollowsCommandsClampedToTheUr5Limit) {
  SimulatedArm arm(ur5_, clock_);
  EXPECT_EQ(arm.Describe(), "simulated UR5 (watchdog 0.5 s)");
  const devices::JointState home = arm.State();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(home.position_rad[i], worlds::Ur5Arm::kHome[i], 1e-6);
  EXPECT_NEAR(home.gripper_opening, 1.0, 0.05);

  arm.CommandJointVelocities({0.3, 0, 0, 0, 0, 10.0});  // joint 6 asks for more than pi rad/s
  for (int step = 0; step < 3; ++step) Advance(arm);
  const devices::JointState moving = arm.State();
  EXPECT_NEAR(moving.timestamp_s, 0.3, 1e-9);
  EXPECT_NEAR(moving.velocity_rad_s[0], 0.3, 0.03);
  EXPECT_NEAR(moving.position_rad[0] - home.position_rad[0], 0.09, 0.01);
  EXPECT_NEAR(moving.velocity_rad_s[5], worlds::Ur5Arm::kMaxJointSpeed_rad_s, 0.1);

  arm.Stop();
  EXPECT_EQ(arm.commanded_velocity_rad_s(), worlds::Ur5Joints{});
  Advance(arm);
  Advance(arm);
  const devices::JointState stopped = arm.State();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(stopped.velocity_rad_s[i], 0.0, 0.01) << "joint " << i;
  EXPECT_FALSE(arm.watchdog_tripped()) << "a stop is a command, not a lapse";
}

TEST_F(SimulatedArmTest, WatchdogStopsAnArmWhoseCommandsStopped) {
  SimulatedArm arm(ur5_, clock_);  // 0.5 s
  arm.CommandJointVelocities({0, 0.4, 0, 0, 0, 0});
  arm.CommandGripper(true);
  std::vector<double> joint2_rad;
  for (int step = 0; step < 12; ++step) {
    Advance(arm);
    joint2_rad.push_back(arm.State().position_rad[1]);
  }
  // Commanded at t = 0 and never again: driven through t = 0.5 s, stopped from the check at
  // t = 0.6 s (the first one more than 0.5 s after the command), still ever since.
  EXPECT_TRUE(arm.watchdog_tripped());
  EXPECT_EQ(arm.commanded_velocity_rad_s(), worlds::Ur5Joints{});
  EXPECT_NEAR(joint2_rad[5] - joint2_rad[0], 0.4 * 0.5, 0.02) << "moving until the timeout";
  // Still after it (driven, it would have moved another 0.16 rad; the servo settles by ~1 mrad).
  EXPECT_NEAR(joint2_rad[11], joint2_rad[7], 0.005);
  EXPECT_NEAR(arm.State().velocity_rad_s[1], 0.0, 0.01);
  EXPECT_TRUE(arm.gripper_closed()) << "the gripper keeps its state";

  // A new command is a new stream: obeyed, and the watchdog rearmed.
  arm.CommandJointVelocities({0, -0.4, 0, 0, 0, 0});
  EXPECT_FALSE(arm.watchdog_tripped());
  Advance(arm);
  Advance(arm);
  EXPECT_LT(arm.State().position_rad[1], joint2_rad[11] - 0.05);
}

TEST_F(SimulatedArmTest, CommandsRenewedInTimeNeverTripAndStateAloneEnforcesTheTimeout) {
  SimulatedArm arm(ur5_, clock_, 0.25);
  for (int step = 0; step < 20; ++step) {
    arm.CommandJointVelocities({0.2, 0, 0, 0, 0, 0});
    Advance(arm);
    Advance(arm);  // commands every 0.2 s: within the 0.25 s timeout
    ASSERT_FALSE(arm.watchdog_tripped()) << "step " << step;
  }
  // Nobody steps or checks; reading the state after the timeout stops the arm.
  clock_.Advance(0.3);
  EXPECT_NE(arm.commanded_velocity_rad_s()[0], 0.0);
  arm.State();
  EXPECT_TRUE(arm.watchdog_tripped());
  EXPECT_EQ(arm.commanded_velocity_rad_s()[0], 0.0);
}

TEST_F(SimulatedArmTest, BadTimeoutIsAUserError) {
  EXPECT_THROW(SimulatedArm(ur5_, clock_, 0.0), UserError);
  EXPECT_THROW(SimulatedArm(ur5_, clock_, -1.0), UserError);
  EXPECT_THROW(SimulatedArm(ur5_, clock_, std::nan("")), UserError);
}

}  // namespace
}  // namespace recon::worlds
