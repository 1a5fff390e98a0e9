// JointKeyboardTeleop: the key map, gripper toggling on presses, Enter.

#include "devices/teleop/joint_keyboard_teleop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace recon::teleop {
namespace {

TEST(JointKeyboardTeleopTest, EachKeyDrivesItsJointAtTheConfiguredSpeed) {
  JointKeyboardTeleop keyboard;  // 0.5 rad/s
  EXPECT_EQ(keyboard.Describe(), "joint keyboard teleop (0.5 rad/s)");
  const std::string plus = "qwerty", minus = "asdfgh";
  for (int joint = 0; joint < 6; ++joint) {
    for (const auto& [key, sign] : {std::pair{plus[joint], 1.0}, std::pair{minus[joint], -1.0}}) {
      keyboard.SetKeyDown(key, true);
      const devices::TeleopCommand command = keyboard.Poll();
      for (int j = 0; j < 6; ++j) {
        EXPECT_EQ(command.joint_velocity_rad_s[j], j == joint ? sign * 0.5 : 0.0)
            << "key " << key << ", joint " << j + 1;
      }
      EXPECT_FALSE(command.close_gripper);
      EXPECT_FALSE(command.finished);
      keyboard.SetKeyDown(key, false);
      EXPECT_EQ(keyboard.Poll().joint_velocity_rad_s, (std::array<double, 6>{})) << key;
    }
  }
}

TEST(JointKeyboardTeleopTest, KeysCombineCancelAndIgnoreCase) {
  JointKeyboardTeleop keyboard(1.25);
  keyboard.SetKeyDown('Q', true);  // Shift held
  keyboard.SetKeyDown('w', true);
  keyboard.SetKeyDown('e', true);
  keyboard.SetKeyDown('d', true);  // joint 3 both ways: cancels
  keyboard.SetKeyDown('x', true);  // not mapped
  EXPECT_EQ(keyboard.Poll().joint_velocity_rad_s, (std::array<double, 6>{1.25, 1.25, 0, 0, 0, 0}));
  keyboard.SetKeyDown('q', false);
  keyboard.SetKeyDown('d', false);
  EXPECT_EQ(keyboard.Poll().joint_velocity_rad_s, (std::array<double, 6>{0, 1.25, 1.25, 0, 0, 0}));
}

TEST(JointKeyboardTeleopTest, SpaceTogglesTheGripperOnPressesOnly) {
  JointKeyboardTeleop keyboard;
  keyboard.SetKeyDown(' ', true);
  EXPECT_TRUE(keyboard.Poll().close_gripper);
  keyboard.SetKeyDown(' ', true);  // auto-repeat while held: not a new press
  EXPECT_TRUE(keyboard.Poll().close_gripper);
  EXPECT_TRUE(keyboard.Poll().close_gripper) << "polling does not toggle";
  keyboard.SetKeyDown(' ', false);
  EXPECT_TRUE(keyboard.Poll().close_gripper) << "releasing does not toggle";
  keyboard.SetKeyDown(' ', true);
  EXPECT_FALSE(keyboard.Poll().close_gripper);
  // A tap between two polls still counts.
  keyboard.SetKeyDown(' ', false);
  keyboard.SetKeyDown(' ', true);
  keyboard.SetKeyDown(' ', false);
  EXPECT_TRUE(keyboard.Poll().close_gripper);
}

TEST(JointKeyboardTeleopTest, EnterFinishesUntilReset) {
  JointKeyboardTeleop keyboard;
  keyboard.SetKeyDown('w', true);
  keyboard.SetKeyDown(' ', true);
  EXPECT_FALSE(keyboard.Poll().finished);
  keyboard.SetKeyDown('\n', true);
  keyboard.SetKeyDown('\n', false);
  EXPECT_TRUE(keyboard.Poll().finished);
  EXPECT_TRUE(keyboard.Poll().finished);
  keyboard.Reset();
  const devices::TeleopCommand fresh = keyboard.Poll();
  EXPECT_FALSE(fresh.finished);
  EXPECT_FALSE(fresh.close_gripper);
  EXPECT_EQ(fresh.joint_velocity_rad_s, (std::array<double, 6>{}));
  keyboard.SetKeyDown('\r', true);  // a terminal's Enter
  EXPECT_TRUE(keyboard.Poll().finished);
}

TEST(JointKeyboardTeleopTest, BadSpeedIsAUserError) {
  EXPECT_THROW(JointKeyboardTeleop(0.0), UserError);
  EXPECT_THROW(JointKeyboardTeleop(-0.5), UserError);
  EXPECT_THROW(JointKeyboardTeleop(std::nan("")), UserError);
}

}  // namespace
}  // namespace recon::teleop
