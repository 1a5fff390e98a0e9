#pragma once

#include "devices/teleop/linux_joystick.h"

namespace recon::teleop {

/// What the sticks and buttons ask of the arm, relative to the camera view (the same axes as the
/// keyboard's): the layout of an Xbox-style pad under the Linux joystick API.
struct GamepadTeleop {
  float screen_right = 0;       ///< left stick, x
  float screen_up = 0;          ///< left stick, y (pushed away: up)
  float raise = 0;              ///< right stick, y (pushed away: up)
  bool toggle_gripper = false;  ///< A (button 0) went down since the last state
  bool keep = false;            ///< Start (button 7) went down: keep the demonstration
};

/// Sticks inside the dead zone read 0, the rest is rescaled so full deflection is still 1.
float DeadZone(float value, float dead_zone = 0.15f);

/// The teleop command of `now`, given the state before it (for the buttons' edges).
GamepadTeleop MapGamepad(const GamepadState& now, const GamepadState& before);

}  // namespace recon::teleop
