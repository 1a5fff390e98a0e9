#include "devices/teleop/gamepad_mapping.h"

#include <cmath>

namespace recon::teleop {

namespace {

float Axis(const GamepadState& s, size_t i) { return i < s.axes.size() ? s.axes[i] : 0.0f; }
bool Button(const GamepadState& s, size_t i) { return i < s.buttons.size() && s.buttons[i]; }

// The joystick API's usual numbering for an Xbox-style pad (xpad): axes 0/1 left stick x/y,
// 3/4 right stick x/y (y grows downwards); buttons 0 A, 1 B, 7 Start.
constexpr size_t kLeftX = 0, kLeftY = 1, kRightY = 4;
constexpr size_t kButtonA = 0, kButtonStart = 7;

}  // namespace

float DeadZone(float value, float dead_zone) {
  if (!std::isfinite(value) || std::abs(value) <= dead_zone) return 0.0f;
  const float magnitude = (std::abs(value) - dead_zone) / (1.0f - dead_zone);
  return std::copysign(std::min(magnitude, 1.0f), value);
}

GamepadTeleop MapGamepad(const GamepadState& now, const GamepadState& before) {
  GamepadTeleop t;
  t.screen_right = DeadZone(Axis(now, kLeftX));
  t.screen_up = -DeadZone(Axis(now, kLeftY));
  t.raise = -DeadZone(Axis(now, kRightY));
  t.toggle_gripper = Button(now, kButtonA) && !Button(before, kButtonA);
  t.keep = Button(now, kButtonStart) && !Button(before, kButtonStart);
  return t;
}

}  // namespace recon::teleop
