#pragma once

#include <string>
#include <vector>

namespace recon::discovery {

/// The kinds of hardware a teaching cell uses.
enum class DeviceKind { kBeacon, kCamera, kGamepad, kRobot };

/// "beacon", "camera", "gamepad", "robot".
const char* DeviceKindName(DeviceKind kind);

/// One device found, and what a probe of it said.
struct FoundDevice {
  DeviceKind kind = DeviceKind::kBeacon;
  /// What to pass to the tools: /dev/ttyACM0, /dev/video0, /dev/input/js0, host:port.
  std::string path;
  /// Who it says it is: the USB product or /dev/serial/by-id name, the joystick's name, "DWM1001
  /// node DECA...", "UR controller 5.11.1.108". Empty when unknown.
  std::string identity;
  /// True when the probe opened it and it answered as its kind should (or, without probing,
  /// when the device file exists).
  bool usable = false;
  /// The probe's finding in a few words, or its error (naming the device).
  std::string detail;
};

/// Where and how to look.
struct DiscoveryOptions {
  /// The device directory (a test points this at a folder of symlinks to pseudo-terminals).
  std::string dev_dir = "/dev";
  /// Open each device briefly: a serial port is asked for the DWM1001 shell, a camera for one
  /// frame, a robot for its RTDE handshake. Without it, devices are listed by their files only.
  bool probe = true;
  int serial_timeout_ms = 1500;
  /// UR controllers to try, "host" or "host:port" (RTDE, default port 30004); robots are on the
  /// network, not in dev_dir, so they are looked for only where the user says.
  std::vector<std::string> robot_hosts;
};

/// Lists the UWB beacons (USB serial ports: ttyACM*, ttyUSB*), cameras (video*), gamepads
/// (input/js*) and robots (robot_hosts) that are there now, in that order and by path within a
/// kind. Never throws for a device that fails its probe: that is reported in its entry.
std::vector<FoundDevice> DiscoverDevices(const DiscoveryOptions& options);

}  // namespace recon::discovery
