#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace recon::teleop {

/// A gamepad's state as the Linux joystick API reports it: axes scaled to -1..1, buttons.
struct GamepadState {
  std::vector<float> axes;
  std::vector<bool> buttons;
  uint32_t time_ms = 0;  ///< the driver's timestamp of the latest event
};

/// A gamepad through the Linux joystick API (/dev/input/jsN, linux/joystick.h): events of 8
/// bytes (time, value, type, number) read without blocking from the file, so the studio's cell
/// thread polls it between frames. Unplugging is reported, not thrown: the teleop stops and the
/// Cell screen shows the error; Reopen() tries again.
class LinuxJoystick {
 public:
  /// Opens `path` (a joystick device, or any file or FIFO that carries js_event records).
  /// UserError naming the path and the reason (missing, no permission).
  explicit LinuxJoystick(std::string path);
  ~LinuxJoystick();
  LinuxJoystick(const LinuxJoystick&) = delete;
  LinuxJoystick& operator=(const LinuxJoystick&) = delete;

  /// Reads every event waiting and applies it; false once the device is gone (unplugged), with
  /// the reason in last_error(). Events split across reads are kept until complete.
  bool Poll();
  const GamepadState& state() const { return state_; }
  const std::string& path() const { return path_; }
  /// The device's name (JSIOCGNAME), or "gamepad" when the file is not a joystick device.
  const std::string& name() const { return name_; }
  bool connected() const { return fd_ >= 0; }
  const std::string& last_error() const { return last_error_; }
  uint64_t events() const { return events_; }

  /// /dev/input/js0, js1, ... that exist now.
  static std::vector<std::string> Find(const std::string& directory = "/dev/input");

 private:
  void Apply(const unsigned char* event);
  void Close(const std::string& why);

  std::string path_;
  std::string name_ = "gamepad";
  int fd_ = -1;
  GamepadState state_;
  std::vector<unsigned char> pending_;  ///< an event's first bytes, until the rest arrives
  std::string last_error_;
  uint64_t events_ = 0;
};

}  // namespace recon::teleop
