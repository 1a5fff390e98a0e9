// The tabletop's UR5 behind its guard (worlds::GuardedUr5), as a real cell's: the e-stop holds it
// whatever a policy asks, the watchdog stops a cell that stops commanding, and a run is the same
// bit for bit however long the world's clock has run.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/rng.h"
#include "engine/worlds/tabletop.h"

namespace recon::worlds {
namespace {

std::unique_ptr<Tabletop> SmallImageTabletop() {
  TabletopOptions options;
  options.image_width = options.image_height = 32;
  return std::make_unique<Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

double LargestJointChange(const Ur5Joints& a, const Ur5Joints& b) {
  double largest = 0;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

// A policy's actions for one step: mostly within a few rad/s, so that the acceleration rule
// changes many of them.
std::vector<float> WildAction(Rng& rng) {
  std::vector<float> u(7);
  for (float& x : u) x = static_cast<float>(rng.Uniform(-2, 2));
  return u;
}

TEST(TabletopGuardedArmTest, TheEStopHoldsTheArmWhateverItIsToldUntilReleased) {
  auto world = SmallImageTabletop();
  world->Reset(7);
  for (int t = 0; t < 20; ++t) world->Step(world->ExpertAction());
  world->guarded_arm().EngageEmergencyStop("test");
  const Ur5Joints held = world->arm().JointPositions();
  const bool gripper = world->arm().GripperClosed();
  const int64_t changed = world->safety_stats().changed;
  Rng rng(4);  // seed 4: 30 steps of a policy that keeps asking to move
  for (int t = 0; t < 30; ++t) world->Step(WildAction(rng));
  // The servo brakes from the expert's speed within a step or two.
  EXPECT_LT(LargestJointChange(held, world->arm().JointPositions()), 0.05);
  for (double v : world->arm().JointVelocities()) EXPECT_LT(std::abs(v), 1e-3);
  EXPECT_EQ(world->arm().GripperClosed(), gripper) << "an e-stop does not open or close it";
  EXPECT_EQ(world->safety_stats().changed, changed + 30);

  world->guarded_arm().ReleaseEmergencyStop();
  const Ur5Joints released = world->arm().JointPositions();
  for (int t = 0; t < 10; ++t) world->Step(world->ExpertAction());
  EXPECT_GT(LargestJointChange(released, world->arm().JointPositions()), 0.01);
}

TEST(TabletopGuardedArmTest, TheWatchdogStopsAnArmWhoseCommandsStopped) {
  auto world = SmallImageTabletop();
  world->Reset(7);
  world->Step({0.3f, 0, 0, 0, 0, 0, 0});
  world->Advance();  // 0.1 s after the command: still in force
  EXPECT_EQ(world->safety_stats().watchdog, 0);
  world->Advance();
  world->Advance();  // 0.3 s: past the 0.2 s watchdog
  EXPECT_EQ(world->safety_stats().watchdog, 1);
  for (int t = 0; t < 5; ++t) world->Advance();
  for (double v : world->arm().JointVelocities()) EXPECT_LT(std::abs(v), 1e-3);
  EXPECT_NEAR(world->clock().NowSeconds(), 0.9, 1e-9);  // 1 step + 8 periods
}

TEST(TabletopGuardedArmTest, ARunIsBitIdenticalHoweverLongTheClockHadRun) {
  auto fresh = SmallImageTabletop(), seasoned = SmallImageTabletop();
  Rng before(8);  // seed 8: 437 steps (43.7 s of clock) in another scene first
  seasoned->Reset(3);
  for (int t = 0; t < 437; ++t) seasoned->Step(WildAction(before));
  fresh->Reset(7);
  seasoned->Reset(7);
  const int64_t limited_before = seasoned->safety_stats().acceleration;
  Rng a(31), b(31);  // seed 31: the same 100 steps for both
  for (int t = 0; t < 100; ++t) {
    fresh->Step(WildAction(a));
    seasoned->Step(WildAction(b));
    ASSERT_EQ(fresh->arm().JointPositions(), seasoned->arm().JointPositions()) << "step " << t;
  }
  // The acceleration rule was at work throughout, so this compares the guard's arithmetic.
  EXPECT_GT(fresh->safety_stats().acceleration, 50);
  EXPECT_EQ(seasoned->safety_stats().acceleration - limited_before,
            fresh->safety_stats().acceleration);
}

}  // namespace
}  // namespace recon::worlds
