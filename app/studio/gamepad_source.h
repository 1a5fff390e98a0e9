#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "devices/teleop/gamepad_mapping.h"
#include "devices/teleop/linux_joystick.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The studio's gamepad: looks for one (every 2 s while none is open), reads its events and
/// turns them into a teleop command; an unplugged pad is remembered with its error until the
/// next one is found. Cell thread only.
class GamepadSource {
 public:
  /// `paths`: the devices to try (empty: /dev/input/js*).
  explicit GamepadSource(std::vector<std::string> paths);

  /// Looks for a pad when none is open and reads the open one's events. True when the pad came
  /// or went, so what the studio shows of it must be rebuilt.
  bool Poll(std::chrono::steady_clock::time_point now);
  bool connected() const { return pad_ && pad_->connected(); }
  /// What the sticks and buttons asked for in the last Poll (button presses as edges).
  const teleop::GamepadTeleop& command() const { return command_; }
  /// Why there is no pad: the open's or the unplug's error (empty while connected).
  const std::string& error() const { return error_; }
  /// Where it looks, for messages: "/dev/input/js*" or the paths given.
  std::string Places() const;
  /// The Cell screen's row for the gamepad.
  ui::DeviceView View() const;

 private:
  std::vector<std::string> paths_;
  std::unique_ptr<teleop::LinuxJoystick> pad_;
  teleop::GamepadState before_;
  teleop::GamepadTeleop command_;
  std::string error_;
  std::chrono::steady_clock::time_point next_scan_{};
};

}  // namespace recon::studio
