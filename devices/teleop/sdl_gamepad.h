#pragma once

#include <memory>
#include <string>

#include "devices/teleop/gamepad_mapping.h"

namespace recon::teleop {

/// A gamepad through SDL2's GameController API: SDL's built-in database of pads (several hundred,
/// plus any the SDL_GAMECONTROLLERCONFIG environment variable adds) maps each one's own button
/// and axis numbers onto the standard layout, so a PlayStation, Switch or off-brand pad drives the
/// arm as an Xbox one does. SDL's joystick subsystem is started once per process on first use,
/// without video or signal handlers. One thread only (the studio's cell thread). Unplugging is
/// reported, not thrown.
class SdlGamepad {
 public:
  /// The first plugged-in pad SDL has a mapping for; nullptr when there is none (then
  /// `*unmapped`, if given, names the joysticks SDL sees without a mapping, which the joystick
  /// API may still read). UserError when SDL's joystick subsystem cannot start.
  static std::unique_ptr<SdlGamepad> OpenFirst(std::string* unmapped = nullptr);
  ~SdlGamepad();
  SdlGamepad(const SdlGamepad&) = delete;
  SdlGamepad& operator=(const SdlGamepad&) = delete;

  /// Reads the pad now; false once it is gone (unplugged), with the reason in last_error().
  bool Poll();
  const StandardPad& state() const { return state_; }
  /// SDL's name for the pad, e.g. "PS4 Controller".
  const std::string& name() const { return name_; }
  /// Where it was found, for the Cell screen: "SDL game controller 0 (mapping: ...)".
  const std::string& where() const { return where_; }
  bool connected() const { return controller_ != nullptr; }
  const std::string& last_error() const { return last_error_; }

 private:
  SdlGamepad(void* controller, int instance_id, std::string name, std::string where);

  void* controller_;  // SDL_GameController*, kept out of this header
  int instance_id_;
  std::string name_, where_;
  StandardPad state_;
  std::string last_error_;
};

/// Starts SDL's game-controller subsystem (once per process; later calls return at once).
/// UserError with SDL's reason when it cannot.
void StartSdlGamepads();

}  // namespace recon::teleop
