// Gamepads through SDL's GameController API, with SDL's own virtual joysticks (no hardware): a
// pad of the standard layout drives the teleop; a pad whose buttons are numbered otherwise drives
// it the same once SDL has a mapping for it (as its built-in database gives for known pads);
// one without a mapping is named, and unplugging is reported.

#include "devices/teleop/sdl_gamepad.h"

#include <SDL2/SDL.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "tests/devices/sdl_virtual_pad.h"

namespace recon::teleop {
namespace {

using ::testing::HasSubstr;

/// A virtual joystick attached for one test and detached after.
class VirtualPad {
 public:
  explicit VirtualPad(const SDL_VirtualJoystickDesc& desc) {
    StartSdlGamepads();
    index_ = SDL_JoystickAttachVirtualEx(&desc);
    EXPECT_GE(index_, 0) << SDL_GetError();
    joystick_ = SDL_JoystickOpen(index_);
    EXPECT_NE(joystick_, nullptr) << SDL_GetError();
  }
  ~VirtualPad() { Unplug(); }

  void Axis(int axis, int16_t value) { SDL_JoystickSetVirtualAxis(joystick_, axis, value); }
  void Button(int button, bool down) { SDL_JoystickSetVirtualButton(joystick_, button, down); }
  SDL_JoystickGUID Guid() const { return SDL_JoystickGetGUID(joystick_); }
  void Unplug() {
    if (joystick_ == nullptr) return;
    SDL_JoystickClose(joystick_);
    joystick_ = nullptr;
    SDL_JoystickDetachVirtual(index_);
  }

 private:
  int index_ = -1;
  SDL_Joystick* joystick_ = nullptr;
};

TEST(SdlGamepadTest, AStandardPadDrivesTheTeleop) {
  VirtualPad virtual_pad(testing::StandardPadDesc("virtual standard pad"));
  std::unique_ptr<SdlGamepad> pad = SdlGamepad::OpenFirst();
  ASSERT_NE(pad, nullptr);
  EXPECT_EQ(pad->name(), "virtual standard pad");
  EXPECT_THAT(pad->where(), HasSubstr("SDL game controller"));
  ASSERT_TRUE(pad->Poll());
  const StandardPad rest = pad->state();
  EXPECT_EQ(MapGamepad(rest, rest).screen_right, 0.0f);

  virtual_pad.Axis(SDL_CONTROLLER_AXIS_LEFTX, 32767);
  virtual_pad.Axis(SDL_CONTROLLER_AXIS_LEFTY, -32768);  // pushed away
  virtual_pad.Axis(SDL_CONTROLLER_AXIS_RIGHTY, 16384);  // pulled half way
  virtual_pad.Button(SDL_CONTROLLER_BUTTON_A, true);
  ASSERT_TRUE(pad->Poll());
  const GamepadTeleop t = MapGamepad(pad->state(), rest);
  EXPECT_FLOAT_EQ(t.screen_right, 1.0f);
  EXPECT_FLOAT_EQ(t.screen_up, 1.0f);
  EXPECT_NEAR(t.raise, -DeadZone(16384.0f / 32767.0f), 1e-6);
  EXPECT_TRUE(t.toggle_gripper);
  EXPECT_FALSE(t.keep);
  const StandardPad held = pad->state();
  ASSERT_TRUE(pad->Poll());
  EXPECT_FALSE(MapGamepad(pad->state(), held).toggle_gripper);  // held, not pressed again
  virtual_pad.Button(SDL_CONTROLLER_BUTTON_START, true);
  ASSERT_TRUE(pad->Poll());
  EXPECT_TRUE(MapGamepad(pad->state(), held).keep);

  // Unplugged: reported, not thrown, and the pad reads at rest.
  virtual_pad.Unplug();
  EXPECT_FALSE(pad->Poll());
  EXPECT_FALSE(pad->connected());
  EXPECT_THAT(pad->last_error(), HasSubstr("virtual standard pad was unplugged"));
  EXPECT_EQ(pad->state(), StandardPad{});
}

// A pad of another maker: its "A" is button 2 and Start button 9, its left stick axes 2 and 3.
// Through the joystick API's xpad numbering it would grip with the wrong button; with a mapping
// (what SDL's database holds for known pads) it drives the arm as an Xbox pad does.
TEST(SdlGamepadTest, APadNumberedOtherwiseDrivesTheArmTheSameOnceMapped) {
  SDL_VirtualJoystickDesc desc{};
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_UNKNOWN;
  desc.naxes = 6;
  desc.nbuttons = 12;
  desc.vendor_id = 0x1234;
  desc.product_id = 0x5678;
  desc.name = "off-brand pad";
  VirtualPad virtual_pad(desc);
  std::string unmapped;
  EXPECT_EQ(SdlGamepad::OpenFirst(&unmapped), nullptr);  // no mapping yet: not a game controller
  EXPECT_THAT(unmapped, HasSubstr("off-brand pad"));

  std::array<char, 64> guid{};
  SDL_JoystickGetGUIDString(virtual_pad.Guid(), guid.data(), static_cast<int>(guid.size()));
  const std::string mapping = std::string(guid.data()) +
                              ",off-brand pad,a:b2,b:b1,start:b9,leftx:a2,lefty:a3,rightx:a4,"
                              "righty:a5,platform:Linux,";
  ASSERT_EQ(SDL_GameControllerAddMapping(mapping.c_str()), 1) << SDL_GetError();
  std::unique_ptr<SdlGamepad> pad = SdlGamepad::OpenFirst();
  ASSERT_NE(pad, nullptr);
  ASSERT_TRUE(pad->Poll());
  const StandardPad rest = pad->state();
  virtual_pad.Button(2, true);  // its "A"
  virtual_pad.Axis(2, 32767);   // its left stick, right
  virtual_pad.Button(0, true);  // where xpad's A would be: nothing here
  ASSERT_TRUE(pad->Poll());
  const GamepadTeleop t = MapGamepad(pad->state(), rest);
  EXPECT_TRUE(t.toggle_gripper);
  EXPECT_FLOAT_EQ(t.screen_right, 1.0f);
  EXPECT_FALSE(pad->state().b);
}

}  // namespace
}  // namespace recon::teleop
