#include "engine/worlds/ur5_arm.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "tests/worlds/ur5_test_scene.h"

namespace recon::worlds {
namespace {

using testing::MakeArmTestScene;

// The UR5's standard DH forward kinematics (REFERENCE.md section 6), flange position.
Eigen::Vector3d DhFlange(const Ur5Joints& q, Eigen::Vector3d* tool_z) {
  const double d[6] = {0.089159, 0, 0, 0.10915, 0.09465, 0.0823};
  const double a[6] = {0, -0.425, -0.39225, 0, 0, 0};
  const double alpha[6] = {M_PI / 2, 0, 0, M_PI / 2, -M_PI / 2, 0};
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  for (int i = 0; i < 6; ++i) {
    const double c = std::cos(q[i]), s = std::sin(q[i]);
    const double ca = std::cos(alpha[i]), sa = std::sin(alpha[i]);
    Eigen::Matrix4d link;
    link << c, -s * ca, s * sa, a[i] * c, s, c * ca, -c * sa, a[i] * s, 0, sa, ca, d[i], 0, 0, 0, 1;
    t = t * link;
  }
  *tool_z = t.block<3, 1>(0, 2);
  return t.block<3, 1>(0, 3);
}

Eigen::Vector3d BodyPosition(const MujocoModel& scene, const char* name) {
  const mjtNum* p = scene.data()->xpos + 3 * mj_name2id(scene.model(), mjOBJ_BODY, name);
  return {p[0], p[1], p[2]};
}

TEST(Ur5ArmTest, MjcfMatchesTheUr5DhKinematics) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  const int flange = mj_name2id(scene.model(), mjOBJ_SITE, "ur5_flange");
  Rng rng(7);  // seed 7: 50 random configurations
  for (int trial = 0; trial < 50; ++trial) {
    Ur5Joints q;
    for (double& v : q) v = rng.Uniform(-3.0, 3.0);
    arm.Reset(q);
    Eigen::Vector3d dh_z;
    const Eigen::Vector3d dh = DhFlange(q, &dh_z);
    const mjtNum* p = scene.data()->site_xpos + 3 * flange;
    const mjtNum* r = scene.data()->site_xmat + 9 * flange;
    EXPECT_NEAR(p[0], dh.x(), 2e-4);
    EXPECT_NEAR(p[1], dh.y(), 2e-4);
    EXPECT_NEAR(p[2], dh.z(), 2e-4);
    EXPECT_NEAR(r[2], dh_z.x(), 1e-6);
    EXPECT_NEAR(r[5], dh_z.y(), 1e-6);
    EXPECT_NEAR(r[8], dh_z.z(), 1e-6);
  }
}

TEST(Ur5ArmTest, IkReachesTargetsWithTheToolDown) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  const int grip = mj_name2id(scene.model(), mjOBJ_SITE, "ur5_grip");
  Rng rng(11);  // seed 11: 40 targets over a 0.4 x 0.7 x 0.35 m box in front of the arm
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d target(rng.Uniform(0.3, 0.7), rng.Uniform(-0.35, 0.35),
                                 rng.Uniform(0.02, 0.37));
    const double yaw = rng.Uniform(-1.5, 1.5);
    const auto q = arm.SolveGraspIk(target, yaw, Ur5Arm::kHome);
    ASSERT_TRUE(q.has_value()) << "target " << target.transpose();
    arm.Reset(*q);
    EXPECT_LT((arm.GripPosition() - target).norm(), 1e-3);
    const mjtNum* r = scene.data()->site_xmat + 9 * grip;
    EXPECT_NEAR(r[8], -1.0, 1e-3) << "tool z must point down";
    // The closing axis (site x) lies at the requested yaw, up to the gripper's symmetry.
    EXPECT_NEAR(std::abs(r[0] * std::cos(yaw) + r[3] * std::sin(yaw)), 1.0, 1e-3);
  }
}

TEST(Ur5ArmTest, UnreachableTargetHasNoSolution) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  EXPECT_FALSE(arm.SolveGraspIk({2.0, 0.0, 0.1}, 0.0, Ur5Arm::kHome).has_value());
}

TEST(Ur5ArmTest, JointSpeedIsLimitedToPiRadiansPerSecond) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  const Ur5Joints before = arm.JointPositions();
  arm.CommandJointVelocities({10.0, 0, 0, 0, 0, -10.0});
  arm.Step(0.5);
  const Ur5Joints after = arm.JointPositions();
  // At most pi * 0.5 s, and the servo keeps up to within a few percent.
  EXPECT_LE(after[0] - before[0], M_PI * 0.5 + 1e-3);
  EXPECT_GT(after[0] - before[0], M_PI * 0.5 * 0.9);
  EXPECT_GE(after[5] - before[5], -M_PI * 0.5 - 1e-3);
  EXPECT_LT(after[5] - before[5], -M_PI * 0.5 * 0.9);
  EXPECT_NEAR(after[1], before[1], 1e-3);
}

TEST(Ur5ArmTest, ZeroCommandHoldsTheArmAgainstGravity) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  arm.Step(0.5);  // settle
  const Ur5Joints before = arm.JointPositions();
  arm.Step(2.0);
  const Ur5Joints after = arm.JointPositions();
  for (int i = 0; i < Ur5Arm::kJoints; ++i) EXPECT_NEAR(after[i], before[i], 1e-4) << "joint " << i;
}

TEST(Ur5ArmTest, NonFiniteCommandStopsInsteadOfMoving) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  arm.Step(0.5);
  const Ur5Joints before = arm.JointPositions();
  arm.CommandJointVelocities({NAN, INFINITY, 0, 0, 0, 0});
  arm.Step(0.5);
  EXPECT_NEAR(arm.JointPositions()[0], before[0], 1e-4);
  EXPECT_NEAR(arm.JointPositions()[1], before[1], 1e-4);
}

TEST(Ur5ArmTest, GripperHoldsTheObjectBetweenItsFingersAndReleasesIt) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  const Eigen::Vector3d box = BodyPosition(scene, "box");
  const auto at_box = arm.SolveGraspIk(box, 0.0, Ur5Arm::kHome);
  ASSERT_TRUE(at_box.has_value());
  arm.Reset(*at_box);
  arm.CommandGripper(true);
  ASSERT_EQ(arm.HeldObject(), mj_name2id(scene.model(), mjOBJ_BODY, "box"));
  arm.Step(0.3);  // the fingers travel at 50 mm/s: 15 of the 44 mm to the box so far
  EXPECT_GT(arm.GripperOpening(), 0.6) << "still closing";
  arm.Step(0.8);
  EXPECT_LT(arm.GripperOpening(), 0.6) << "fingers close onto the 4 cm box";
  EXPECT_GT(arm.GripperOpening(), 0.2) << "but not through it";

  arm.CommandJointVelocities({0.0, -0.5, 0.0, 0.0, 0.0, 0.0});  // shoulder lift raises the arm
  arm.Step(0.8);
  arm.CommandJointVelocities({});
  arm.Step(0.3);
  const Eigen::Vector3d lifted = BodyPosition(scene, "box");
  EXPECT_GT(lifted.z(), 0.15);
  EXPECT_LT((lifted - arm.GripPosition()).norm(), 0.005) << "the box stays in the grip";

  arm.CommandGripper(false);
  EXPECT_EQ(arm.HeldObject(), -1);
  arm.Step(1.0);
  EXPECT_LT(BodyPosition(scene, "box").z(), 0.03) << "released, the box falls to the floor";
}

TEST(Ur5ArmTest, ClosingOnNothingHoldsNothing) {
  MujocoModel scene = MakeArmTestScene();
  Ur5Arm arm(scene);
  arm.CommandGripper(true);
  EXPECT_EQ(arm.HeldObject(), -1);
  arm.Step(1.4);  // 60 mm at 50 mm/s
  EXPECT_LT(arm.GripperOpening(), 0.05);
  EXPECT_EQ(arm.HeldObject(), -1);
}

TEST(Ur5ArmTest, SceneWithoutTheArmIsAClearError) {
  MujocoModel scene = MujocoModel::FromString("<mujoco><worldbody/></mujoco>", "bare");
  try {
    Ur5Arm arm(scene);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("ur5_shoulder_pan"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace recon::worlds
