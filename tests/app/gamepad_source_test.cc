// The studio's gamepad source finds a pad through SDL's GameController API (an SDL virtual
// joystick here), turns its sticks and buttons into the teleop command, shows it on the Cell
// screen's row, and reports it unplugged.

#include "app/studio/gamepad_source.h"

#include <SDL2/SDL.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>

#include "devices/teleop/sdl_gamepad.h"
#include "tests/devices/sdl_virtual_pad.h"

namespace recon::studio {
namespace {

using ::testing::HasSubstr;

TEST(GamepadSourceTest, FindsAnSdlPadDrivesTheTeleopAndReportsItUnplugged) {
  teleop::StartSdlGamepads();
  const SDL_VirtualJoystickDesc desc = teleop::testing::StandardPadDesc("studio test pad");
  const int index = SDL_JoystickAttachVirtualEx(&desc);
  ASSERT_GE(index, 0) << SDL_GetError();
  SDL_Joystick* joystick = SDL_JoystickOpen(index);
  ASSERT_NE(joystick, nullptr);

  GamepadSource source({});  // no paths: SDL's pads first
  auto now = std::chrono::steady_clock::now();
  EXPECT_TRUE(source.Poll(now));  // it came
  ASSERT_TRUE(source.connected()) << source.error();
  const ui::DeviceView row = source.View();
  EXPECT_TRUE(row.connected);
  EXPECT_THAT(row.detail, HasSubstr("studio test pad (SDL game controller"));

  SDL_JoystickSetVirtualAxis(joystick, SDL_CONTROLLER_AXIS_LEFTY, -32768);
  SDL_JoystickSetVirtualButton(joystick, SDL_CONTROLLER_BUTTON_A, 1);
  now += std::chrono::milliseconds(10);
  EXPECT_FALSE(source.Poll(now));  // nothing came or went
  EXPECT_FLOAT_EQ(source.command().screen_up, 1.0f);
  EXPECT_TRUE(source.command().toggle_gripper);

  SDL_JoystickClose(joystick);
  SDL_JoystickDetachVirtual(index);
  now += std::chrono::milliseconds(10);
  EXPECT_TRUE(source.Poll(now));  // it went
  EXPECT_FALSE(source.connected());
  EXPECT_THAT(source.error(), HasSubstr("studio test pad was unplugged"));
  EXPECT_THAT(source.View().last_error, HasSubstr("unplugged"));
  EXPECT_EQ(source.command().screen_up, 0.0f);
}

}  // namespace
}  // namespace recon::studio
