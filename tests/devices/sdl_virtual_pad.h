#pragma once

// An SDL virtual joystick of the standard layout, for the gamepad tests (no hardware).

#include <SDL2/SDL.h>

namespace recon::teleop::testing {

/// A virtual game controller: SDL maps its axes and buttons in SDL's own order, so index k of
/// each is SDL_CONTROLLER_AXIS_k / SDL_CONTROLLER_BUTTON_k.
inline SDL_VirtualJoystickDesc StandardPadDesc(const char* name) {
  SDL_VirtualJoystickDesc desc{};
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_GAMECONTROLLER;
  desc.naxes = SDL_CONTROLLER_AXIS_MAX;
  desc.nbuttons = SDL_CONTROLLER_BUTTON_MAX;
  desc.axis_mask = (1u << SDL_CONTROLLER_AXIS_MAX) - 1;
  desc.button_mask = (1u << SDL_CONTROLLER_BUTTON_MAX) - 1;
  desc.name = name;
  return desc;
}

}  // namespace recon::teleop::testing
