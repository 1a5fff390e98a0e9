#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "devices/teleop/gamepad_mapping.h"
#include "devices/teleop/linux_joystick.h"
#include "devices/teleop/sdl_gamepad.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The studio's gamepad: looks for one (every 2 s while none is open), reads it and turns it
/// into a teleop command; an unplugged pad is remembered with its error until the next one is
/// found. Pads are looked for through SDL's GameController API first (its mapping database puts
/// any known pad's buttons where an Xbox pad has them), then through the Linux joystick API with
/// the xpad numbering; given paths (a FIFO in tests) are read through the joystick API only.
/// Cell thread only.
class GamepadSource {
 public:
  /// `paths`: the joystick devices to try (empty: SDL's pads, then /dev/input/js*).
  explicit GamepadSource(std::vector<std::string> paths);
  ~GamepadSource();

  /// Looks for a pad when none is open and reads the open one's events. True when the pad came
  /// or went, so what the studio shows of it must be rebuilt.
  bool Poll(std::chrono::steady_clock::time_point now);
  bool connected() const { return (sdl_ && sdl_->connected()) || (pad_ && pad_->connected()); }
  /// What the sticks and buttons asked for in the last Poll (button presses as edges).
  const teleop::GamepadTeleop& command() const { return command_; }
  /// Why there is no pad: the open's or the unplug's error (empty while connected).
  const std::string& error() const { return error_; }
  /// Where it looks, for messages: "SDL's game controllers, /dev/input/js*" or the paths given.
  std::string Places() const;
  /// The Cell screen's row for the gamepad.
  ui::DeviceView View() const;

 private:
  std::vector<std::string> paths_;
  /// Opens the first pad found; true when one was.
  bool Scan();

  std::unique_ptr<teleop::SdlGamepad> sdl_;
  std::unique_ptr<teleop::LinuxJoystick> pad_;
  teleop::StandardPad before_;
  teleop::GamepadTeleop command_;
  std::string error_;
  std::chrono::steady_clock::time_point next_scan_{};
};

}  // namespace recon::studio
