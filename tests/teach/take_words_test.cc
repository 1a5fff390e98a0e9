// What a teacher is told as a person's take ends (teach::TakeWords), on the simulated tabletop
// driven by the Cartesian teleop a person's keys drive: a take left standing, the toast dropped
// half-way, dropped off the table, picked up twice.

#include "engine/teach/take_words.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "devices/render/mujoco_renderer.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/worlds/tabletop.h"

namespace recon::teach {
namespace {

class TakeWordsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    world_ = std::make_unique<worlds::Tabletop>(worlds::TabletopOptions{},
                                                std::make_unique<render::MujocoRenderer>());
    world_->ResetToLayout(1, {0.6, -0.25, 0.0}, {0.56, 0.33, 0.0});
  }

  /// One period of the teleop, recorded as a take's sample is.
  void Step(const TeleopCommand& command) {
    Sample sample;
    sample.u = CartesianTeleopAction(*world_, command);
    world_->Step(sample.u);
    take_.samples.push_back(std::move(sample));
  }
  /// Drives the grip point to `target` (table frame) as a held key would; true within 2 mm.
  bool MoveGripTo(const Eigen::Vector3d& target, bool closed) {
    for (int step = 0; step < 400; ++step) {
      const Eigen::Vector3d off = target - world_->arm().GripPosition();
      if (off.norm() < 0.002) return true;
      TeleopCommand command;
      Eigen::Vector3d velocity = off / 0.1;
      if (velocity.norm() > 0.1) velocity *= 0.1 / velocity.norm();
      command.velocity_m_s = velocity;
      command.close_gripper = closed;
      Step(command);
    }
    return false;
  }
  void Wait(double seconds, bool closed) {
    TeleopCommand command;
    command.close_gripper = closed;
    for (int i = 0; i < static_cast<int>(std::lround(seconds / 0.1)); ++i) Step(command);
  }
  /// Down onto the toast, closed, and up to `lift_m`: holding it.
  void PickUp(double lift_m) {
    Eigen::Vector3d above = world_->ToastPosition();
    above.z() = 0.08;
    ASSERT_TRUE(MoveGripTo(above, false));
    const auto [low, high] = world_->GraspHeights();
    above.z() = 0.5 * (low + high);
    ASSERT_TRUE(MoveGripTo(above, false));
    Wait(1.0, true);
    above.z() = lift_m;
    ASSERT_TRUE(MoveGripTo(above, true));
    ASSERT_GE(world_->arm().HeldObject(), 0) << "holding the toast";
  }
  std::string Words(bool done) const { return TakeWords(*world_, take_, done); }

  std::unique_ptr<worlds::Tabletop> world_;
  Episode take_;
};

TEST_F(TakeWordsTest, ATakeLeftStandingSaysForHowLongAndThatNothingWasPickedUp) {
  Wait(10.0, false);
  EXPECT_DOUBLE_EQ(LongestStillSeconds(take_, world_->ActionNoiseScale(), 0.1), 10.0);
  EXPECT_EQ(Words(false), "it never picked the toast up; the arm stood still for 10.0 s");
  // A look of under 5 s is a person thinking: no word.
  take_ = {};
  Wait(4.0, false);
  EXPECT_EQ(Words(false), "it never picked the toast up");
}

TEST_F(TakeWordsTest, TheToastDroppedHalfWaySaysHowFarFromThePlate) {
  PickUp(0.10);
  Eigen::Vector3d half_way = 0.5 * (world_->arm().GripPosition() + world_->PlatePosition());
  half_way.z() = 0.10;
  ASSERT_TRUE(MoveGripTo(half_way, true));
  Wait(1.5, false);  // let go, and it falls
  const int cm = static_cast<int>(std::lround(world_->EpisodeMetric() * 100));
  ASSERT_GT(cm, 5) << "it fell well away from the plate";
  EXPECT_EQ(Words(false),
            "it let the toast go off the plate, " + std::to_string(cm) + " cm from its middle");
  EXPECT_FALSE(world_->TaskSucceeded());
}

TEST_F(TakeWordsTest, TheToastDroppedOffTheTableIsSaid) {
  PickUp(0.15);
  // Past the table's left edge (y = 0.6 m), within the arm's reach.
  ASSERT_TRUE(MoveGripTo({0.35, 0.68, 0.15}, true));
  Wait(2.0, false);
  EXPECT_LT(world_->ToastPosition().z(), -0.03) << "it fell below the table's top";
  EXPECT_EQ(Words(false).rfind("it dropped the toast off the table", 0), 0u) << Words(false);
}

TEST_F(TakeWordsTest, ARegraspIsCountedAndADoneTakeSaysNothingElse) {
  PickUp(0.03);
  Wait(1.0, false);  // let go: it drops 2 cm back onto the table
  PickUp(0.05);
  EXPECT_EQ(Words(true), "the toast was picked up 2 times");
  EXPECT_EQ(world_->OutcomeDetails().at("grasps"), 2.0);
}

}  // namespace
}  // namespace recon::teach
