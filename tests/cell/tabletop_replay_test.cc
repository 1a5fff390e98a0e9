// Playing a tabletop rollout back: the state kept at a step draws, in another world, the same
// scene and the same camera frame the policy saw at that step.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/world_factory.h"

namespace recon::worlds {
namespace {

using ::testing::HasSubstr;

std::unique_ptr<Tabletop> ReplayTabletop() {
  TabletopOptions options;
  options.placement = "none";  // as rollouts run
  return std::make_unique<Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

/// What a viewer draws at one step.
struct Frame {
  std::vector<double> state;
  RgbImage image;
  Eigen::Vector3d toast, plate, bowl, grip;
};

Frame Capture(Tabletop& world) {
  return {world.ReplayState(),   world.CameraImage(),  world.ToastPosition(),
          world.PlatePosition(), world.BowlPosition(), world.arm().GripPosition()};
}

size_t DifferentBytes(const RgbImage& a, const RgbImage& b) {
  if (a.rgb.size() != b.rgb.size()) return std::max(a.rgb.size(), b.rgb.size());
  size_t different = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) different += a.rgb[i] != b.rgb[i] ? 1 : 0;
  return different;
}

void ExpectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, const char* what) {
  EXPECT_LT((actual - expected).norm(), 1e-9)
      << what << " at (" << actual.transpose() << "), was (" << expected.transpose() << ")";
}

TEST(TabletopReplayTest, ShownStateRedrawsTheFrameOfItsStep) {
  auto world = ReplayTabletop();
  world->Reset(104);  // seed 104: the expert grasps, carries and releases the toast
  std::vector<Frame> frames = {Capture(*world)};
  std::vector<int> held_steps;
  for (int t = 1; t <= world->EpisodeLength(); ++t) {
    world->Step(world->ExpertAction());
    frames.push_back(Capture(*world));
    if (world->arm().HeldObject() >= 0) held_steps.push_back(t);
  }
  ASSERT_TRUE(world->TaskSucceeded());
  ASSERT_GT(held_steps.size(), 20u) << "the expert never carried the toast";
  for (const Frame& f : frames) ASSERT_EQ(f.state.size(), frames[0].state.size());
  EXPECT_EQ(static_cast<int>(frames[0].state.size()), world->ReplayStateSize());

  // The viewer's world starts in another scenario, so everything shown must come from the state.
  auto viewer = ReplayTabletop();
  uint64_t viewer_seed = 7;  // the first seed from 7 on whose plate is on the other side
  do {
    viewer->Reset(viewer_seed++);
  } while ((viewer->PlatePosition() - frames[0].plate).norm() < 0.1);
  ASSERT_GT((viewer->PlatePosition() - frames[0].plate).norm(), 0.1);
  // Reset, mid-carry (the toast moves with the gripper), just after the release, and the end.
  const int carry = held_steps[held_steps.size() / 2];
  const std::vector<int> checked = {0, 5, carry, held_steps.back() + 1, world->EpisodeLength()};
  for (int k : checked) {
    SCOPED_TRACE("step " + std::to_string(k));
    const Frame& original = frames[static_cast<size_t>(k)];
    viewer->ShowReplayState(original.state);
    ExpectNear(viewer->ToastPosition(), original.toast, "toast");
    ExpectNear(viewer->PlatePosition(), original.plate, "plate");
    ExpectNear(viewer->BowlPosition(), original.bowl, "bowl");
    ExpectNear(viewer->arm().GripPosition(), original.grip, "grip");
    EXPECT_EQ(DifferentBytes(viewer->CameraImage(), original.image), 0u);
    // Shown at rest, the state reads back as it was given.
    const std::vector<double> again = viewer->ReplayState();
    ASSERT_EQ(again.size(), original.state.size());
    for (size_t i = 0; i < again.size(); ++i) EXPECT_NEAR(again[i], original.state[i], 1e-12) << i;
  }
  // The comparison can tell steps apart: mid-carry the arm moves visibly from step to step.
  EXPECT_GT(DifferentBytes(frames[carry].image, frames[carry + 1].image), 0u);
  EXPECT_GT((frames[carry].toast - frames[carry + 1].toast).norm(), 1e-4);
}

TEST(TabletopReplayTest, WrongSizeOrNonFiniteStateIsRefusedAndChangesNothing) {
  auto world = ReplayTabletop();
  world->Reset(3);
  const std::vector<double> state = world->ReplayState();
  const RgbImage image = world->CameraImage();
  const int size = world->ReplayStateSize();
  ASSERT_GT(size, 0);
  std::vector<double> short_state(state.begin(), state.end() - 1);
  try {
    world->ShowReplayState(short_state);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("has " + std::to_string(size) + " values"));
    EXPECT_THAT(e.what(), HasSubstr("got " + std::to_string(size - 1)));
  }
  EXPECT_THROW(world->ShowReplayState({}), UserError);
  std::vector<double> bad = state;
  bad[2] = std::numeric_limits<double>::quiet_NaN();
  try {
    world->ShowReplayState(bad);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("value 2 is not finite"));
  }
  EXPECT_EQ(world->ReplayState(), state);
  EXPECT_EQ(DifferentBytes(world->CameraImage(), image), 0u);
}

TEST(TabletopReplayTest, WorldsWithoutReplaySaySo) {
  for (const char* name : {"static2d", "dynamic2d"}) {
    SCOPED_TRACE(name);
    auto world = MakeWorld(name, "none", 0.0, false);
    world->Reset(1);
    EXPECT_TRUE(world->ReplayState().empty());
    try {
      world->ShowReplayState({1.0, 2.0});
      FAIL() << "expected UserError";
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("has no replay"));
      EXPECT_THAT(e.what(), HasSubstr(name));
    }
  }
}

}  // namespace
}  // namespace recon::worlds
