#include "devices/teleop/gamepad_mapping.h"

#include <cmath>

namespace recon::teleop {

namespace {

float Axis(const GamepadState& s, size_t i) { return i < s.axes.size() ? s.axes[i] : 0.0f; }
bool Button(const GamepadState& s, size_t i) { return i < s.buttons.size() && s.buttons[i]; }

// The joystick API's usual numbering for an Xbox-style pad (xpad): axes 0/1 left stick x/y,
// 3/4 right stick x/y (y grows downwards); buttons 0 A, 1 B, 7 Start.
constexpr size_t kLeftX = 0, kLeftY = 1, kRightX = 3, kRightY = 4;
constexpr size_t kButtonA = 0, kButtonB = 1, kButtonStart = 7;

}  // namespace

float DeadZone(float value, float dead_zone) {
  if (!std::isfinite(value) || std::abs(value) <= dead_zone) return 0.0f;
  const float magnitude = (std::abs(value) - dead_zone) / (1.0f - dead_zone);
  return std::copysign(std::min(magnitude, 1.0f), value);
}

StandardPad FromXpadNumbering(const GamepadState& joystick) {
  StandardPad pad;
  pad.left_x = Axis(joystick, kLeftX);
  pad.left_y = Axis(joystick, kLeftY);
  pad.right_x = Axis(joystick, kRightX);
  pad.right_y = Axis(joystick, kRightY);
  pad.a = Button(joystick, kButtonA);
  pad.b = Button(joystick, kButtonB);
  pad.start = Button(joystick, kButtonStart);
  return pad;
}

GamepadTeleop MapGamepad(const StandardPad& now, const StandardPad& before) {
  GamepadTeleop t;
  t.screen_right = DeadZone(now.left_x);
  t.screen_up = -DeadZone(now.left_y);
  t.raise = -DeadZone(now.right_y);
  // The right stick sideways turns the wrist: pushed right, clockwise seen from above.
  t.turn = -DeadZone(now.right_x);
  t.toggle_gripper = now.a && !before.a;
  t.keep = now.start && !before.start;
  return t;
}

GamepadTeleop MapGamepad(const GamepadState& now, const GamepadState& before) {
  return MapGamepad(FromXpadNumbering(now), FromXpadNumbering(before));
}

}  // namespace recon::teleop
