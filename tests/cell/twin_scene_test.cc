// The twin's kinematic grasp: the gripper closed around the toast carries it, opened over the
// plate puts it on the plate, opened elsewhere drops it on the table; a gripper closed beside the
// toast carries nothing.

#include "devices/cell/twin_scene.h"

#include <gtest/gtest.h>

#include "engine/worlds/scene_assets.h"

namespace recon::cell {
namespace {

class TwinSceneTest : public ::testing::Test {
 protected:
  TwinSceneTest() : ik_scene_(worlds::LoadScene("tabletop")), ik_(ik_scene_) {}

  /// The joints that put the grip point at `p` (table frame), tool down.
  worlds::Ur5Joints At(const Eigen::Vector3d& p) {
    const std::optional<worlds::Ur5Joints> q = ik_.SolveGraspIk(p, 0.0, worlds::Ur5Arm::kHome);
    EXPECT_TRUE(q.has_value()) << p.transpose();
    return q.value_or(worlds::Ur5Arm::kHome);
  }

  worlds::MujocoModel ik_scene_;
  worlds::Ur5Arm ik_;  // only for its inverse kinematics
  TwinScene twin_;
};

TEST_F(TwinSceneTest, AClosedGripperCarriesTheToastToThePlateAndLetsItGoThere) {
  TwinLayout layout;
  layout.toast = {0.40, 0.05};
  layout.plate = {0.55, 0.30};
  twin_.Arrange(layout);
  const Eigen::Vector3d rest = twin_.ToastPosition();
  EXPECT_NEAR(rest.x(), 0.40, 1e-9);
  // Down over the toast, open; close; lift and carry; open over the plate.
  twin_.PoseArm(At({0.40, 0.05, 0.10}), 1.0);
  twin_.PoseArm(At({0.40, 0.05, 0.012}), 1.0);
  EXPECT_FALSE(twin_.HoldsToast());
  twin_.PoseArm(At({0.40, 0.05, 0.012}), 0.0);
  ASSERT_TRUE(twin_.HoldsToast());
  twin_.PoseArm(At({0.50, 0.20, 0.15}), 0.0);
  EXPECT_NEAR(twin_.ToastPosition().x(), 0.50, 0.005);
  EXPECT_NEAR(twin_.ToastPosition().y(), 0.20, 0.005);
  EXPECT_GT(twin_.ToastPosition().z(), 0.12);
  twin_.PoseArm(At({0.55, 0.30, 0.08}), 0.0);
  twin_.PoseArm(At({0.55, 0.30, 0.08}), 1.0);
  EXPECT_FALSE(twin_.HoldsToast());
  const Eigen::Vector3d on_plate = twin_.ToastPosition();
  EXPECT_NEAR(on_plate.x(), 0.55, 0.005);
  EXPECT_NEAR(on_plate.y(), 0.30, 0.005);
  EXPECT_NEAR(on_plate.z(), rest.z() + 0.012, 1e-9);  // on the plate's 12 mm top
  // The arm leaves; the toast stays.
  twin_.PoseArm(worlds::Ur5Arm::kHome, 1.0);
  EXPECT_EQ(twin_.ToastPosition(), on_plate);
  // Picked up again and dropped off the plate: it lands on the table.
  twin_.PoseArm(At({0.55, 0.30, 0.022}), 1.0);
  twin_.PoseArm(At({0.55, 0.30, 0.022}), 0.0);
  ASSERT_TRUE(twin_.HoldsToast());
  twin_.PoseArm(At({0.35, -0.2, 0.1}), 0.0);
  twin_.PoseArm(At({0.35, -0.2, 0.1}), 1.0);
  EXPECT_NEAR(twin_.ToastPosition().z(), rest.z(), 1e-9);
  EXPECT_NEAR(twin_.ToastPosition().y(), -0.2, 0.005);
}

TEST_F(TwinSceneTest, AGripperClosedBesideTheToastOrAboveItCarriesNothing) {
  twin_.Arrange(TwinLayout{});                  // the toast at (0.35, 0)
  twin_.PoseArm(At({0.35, 0.08, 0.012}), 0.0);  // 8 cm beside it
  EXPECT_FALSE(twin_.HoldsToast());
  twin_.PoseArm(At({0.35, 0.0, 0.15}), 1.0);
  twin_.PoseArm(At({0.35, 0.0, 0.15}), 0.0);  // 14 cm above it
  EXPECT_FALSE(twin_.HoldsToast());
  // Closed before it came down: it does not pick the toast up by touching it.
  twin_.PoseArm(At({0.35, 0.0, 0.012}), 0.0);
  EXPECT_FALSE(twin_.HoldsToast());
  EXPECT_NEAR(twin_.ToastPosition().x(), 0.35, 1e-9);
  // A new layout takes a held toast from the gripper: the person put it elsewhere.
  twin_.PoseArm(At({0.35, 0.0, 0.012}), 1.0);
  twin_.PoseArm(At({0.35, 0.0, 0.012}), 0.0);
  ASSERT_TRUE(twin_.HoldsToast());
  TwinLayout moved;
  moved.toast = {0.3, -0.1};
  twin_.Arrange(moved);
  EXPECT_FALSE(twin_.HoldsToast());
  EXPECT_NEAR(twin_.ToastPosition().y(), -0.1, 1e-9);
}

}  // namespace
}  // namespace recon::cell
