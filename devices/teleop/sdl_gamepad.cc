#include "devices/teleop/sdl_gamepad.h"

#include <SDL2/SDL.h>

#include <mutex>

#include "engine/core/error.h"

namespace recon::teleop {

namespace {

float AxisValue(SDL_GameController* pad, SDL_GameControllerAxis axis) {
  // -32768..32767 to -1..1.
  return static_cast<float>(SDL_GameControllerGetAxis(pad, axis)) / 32767.0f;
}

bool ButtonValue(SDL_GameController* pad, SDL_GameControllerButton button) {
  return SDL_GameControllerGetButton(pad, button) != 0;
}

}  // namespace

void StartSdlGamepads() {
  static std::once_flag once;
  static std::string failure;
  std::call_once(once, [] {
    // The studio owns its window and its signals; SDL is here for the pads only. HIDAPI drivers
    // would start threads of their own for pads the kernel already serves.
    SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
    SDL_SetHint(SDL_HINT_JOYSTICK_ALLOW_BACKGROUND_EVENTS, "1");
    SDL_SetHint(SDL_HINT_JOYSTICK_HIDAPI, "0");
    if (SDL_InitSubSystem(SDL_INIT_GAMECONTROLLER) != 0) failure = SDL_GetError();
  });
  if (!failure.empty()) throw UserError("SDL's game controllers cannot start: " + failure);
}

std::unique_ptr<SdlGamepad> SdlGamepad::OpenFirst(std::string* unmapped) {
  StartSdlGamepads();
  SDL_GameControllerUpdate();  // picks up pads plugged in since the last look
  SDL_PumpEvents();
  std::string without_mapping;
  for (int i = 0; i < SDL_NumJoysticks(); ++i) {
    if (!SDL_IsGameController(i)) {
      const char* name = SDL_JoystickNameForIndex(i);
      without_mapping += (without_mapping.empty() ? "" : ", ") + std::string(name ? name : "?");
      continue;
    }
    SDL_GameController* pad = SDL_GameControllerOpen(i);
    if (pad == nullptr) continue;
    const char* name = SDL_GameControllerName(pad);
    const int instance = SDL_JoystickInstanceID(SDL_GameControllerGetJoystick(pad));
    return std::unique_ptr<SdlGamepad>(
        new SdlGamepad(pad, instance, name ? name : "gamepad",
                       "SDL game controller " + std::to_string(i) + " (standard mapping)"));
  }
  if (unmapped != nullptr) *unmapped = without_mapping;
  return nullptr;
}

SdlGamepad::SdlGamepad(void* controller, int instance_id, std::string name, std::string where)
    : controller_(controller),
      instance_id_(instance_id),
      name_(std::move(name)),
      where_(std::move(where)) {}

SdlGamepad::~SdlGamepad() {
  if (controller_ != nullptr)
    SDL_GameControllerClose(static_cast<SDL_GameController*>(controller_));
}

bool SdlGamepad::Poll() {
  if (controller_ == nullptr) return false;
  SDL_GameControllerUpdate();
  SDL_PumpEvents();
  auto* pad = static_cast<SDL_GameController*>(controller_);
  if (!SDL_GameControllerGetAttached(pad)) {
    SDL_GameControllerClose(pad);
    controller_ = nullptr;
    last_error_ = name_ + " was unplugged";
    state_ = {};
    return false;
  }
  state_.left_x = AxisValue(pad, SDL_CONTROLLER_AXIS_LEFTX);
  state_.left_y = AxisValue(pad, SDL_CONTROLLER_AXIS_LEFTY);
  state_.right_x = AxisValue(pad, SDL_CONTROLLER_AXIS_RIGHTX);
  state_.right_y = AxisValue(pad, SDL_CONTROLLER_AXIS_RIGHTY);
  state_.a = ButtonValue(pad, SDL_CONTROLLER_BUTTON_A);
  state_.b = ButtonValue(pad, SDL_CONTROLLER_BUTTON_B);
  state_.start = ButtonValue(pad, SDL_CONTROLLER_BUTTON_START);
  return true;
}

}  // namespace recon::teleop
