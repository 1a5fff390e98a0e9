#pragma once

#include "devices/teleop/linux_joystick.h"

namespace recon::teleop {

/// A pad in the standard layout (SDL's GameController: an Xbox pad's names, whatever the pad's
/// own numbering): sticks -1..1 with y growing downwards, as pads report them, and buttons.
struct StandardPad {
  float left_x = 0, left_y = 0, right_x = 0, right_y = 0;
  bool a = false, b = false, start = false;
  bool operator==(const StandardPad& other) const = default;
};

/// A joystick-API state read with the xpad driver's numbering (axes 0/1 left stick, 3/4 right
/// stick; buttons 0 A, 1 B, 7 Start): the fallback for pads SDL has no mapping for.
StandardPad FromXpadNumbering(const GamepadState& joystick);

/// What the sticks and buttons ask of the arm, relative to the camera view (the same axes as the
/// keyboard's).
struct GamepadTeleop {
  float screen_right = 0;       ///< left stick, x
  float screen_up = 0;          ///< left stick, y (pushed away: up)
  float raise = 0;              ///< right stick, y (pushed away: up)
  float turn = 0;               ///< right stick, x (pushed left: the wrist counter-clockwise)
  bool toggle_gripper = false;  ///< A went down since the last state
  bool keep = false;            ///< Start went down: keep the demonstration
};

/// Sticks inside the dead zone read 0, the rest is rescaled so full deflection is still 1.
float DeadZone(float value, float dead_zone = 0.15f);

/// The teleop command of `now`, given the state before it (for the buttons' edges).
GamepadTeleop MapGamepad(const StandardPad& now, const StandardPad& before);
/// The same for a joystick-API pad read with the xpad numbering.
GamepadTeleop MapGamepad(const GamepadState& now, const GamepadState& before);

}  // namespace recon::teleop
