#include "devices/discovery/device_discovery.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>

#include "devices/camera/open_camera.h"
#include "devices/robot/rtde_client.h"
#include "devices/teleop/linux_joystick.h"
#include "devices/uwb/dwm1001_driver.h"

namespace recon::discovery {
namespace fs = std::filesystem;
namespace {

/// Files in `dir` whose names start with one of `prefixes`, sorted (ttyACM0 before ttyACM1).
std::vector<std::string> Matching(const fs::path& dir, const std::vector<std::string>& prefixes) {
  std::vector<std::string> found;
  std::error_code error;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    for (const std::string& prefix : prefixes) {
      if (name.rfind(prefix, 0) == 0) found.push_back(it->path().string());
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string Canonical(const std::string& path) {
  std::error_code error;
  const fs::path resolved = fs::canonical(path, error);
  return error ? path : resolved.string();
}

/// A USB serial adapter's identity: its /dev/serial/by-id name (what udev made of the USB
/// descriptors, e.g. "usb-SEGGER_J-Link_000760012345-if00"), else sysfs's product string.
std::string SerialIdentity(const std::string& port, const fs::path& dev_dir) {
  const std::string target = Canonical(port);
  for (const std::string& link : Matching(dev_dir / "serial" / "by-id", {""})) {
    if (Canonical(link) == target) return fs::path(link).filename().string();
  }
  std::ifstream product("/sys/class/tty/" + fs::path(target).filename().string() +
                        "/device/../product");
  std::string line;
  if (product && std::getline(product, line)) return line;
  return "";
}

FoundDevice ProbeBeacon(const std::string& port, const DiscoveryOptions& options) {
  FoundDevice found{DeviceKind::kBeacon, port, SerialIdentity(port, options.dev_dir), true,
                    "serial port"};
  if (!options.probe) return found;
  try {
    uwb::Dwm1001Options dwm;
    dwm.answer_timeout_ms = options.serial_timeout_ms;
    uwb::Dwm1001Driver driver(port, dwm);
    const std::string node = uwb::NodeIdHex(driver.node_id());
    found.identity = "DWM1001 node " + node;
    found.detail = "PANS shell answered; the anchors know it as " + node.substr(12);
  } catch (const std::exception& e) {
    found.usable = false;
    found.detail = e.what();
  }
  return found;
}

FoundDevice ProbeCamera(const std::string& path, const DiscoveryOptions& options) {
  FoundDevice found{DeviceKind::kCamera, path, "", true, "video device"};
  if (!options.probe) return found;
  try {
    const std::unique_ptr<devices::Camera> camera = camera::OpenCamera(path);
    const devices::CameraFrame frame = camera->Capture();
    found.identity = camera->Describe();
    found.detail = "delivered a " + std::to_string(frame.image.width) + "x" +
                   std::to_string(frame.image.height) + " frame";
  } catch (const std::exception& e) {
    // V4L2 also makes metadata nodes (every other /dev/videoN of a UVC camera): they cannot
    // capture, and say so here.
    found.usable = false;
    found.detail = e.what();
  }
  return found;
}

FoundDevice ProbeGamepad(const std::string& path, const DiscoveryOptions& options) {
  FoundDevice found{DeviceKind::kGamepad, path, "", true, "joystick device"};
  if (!options.probe) return found;
  try {
    teleop::LinuxJoystick joystick(path);
    found.identity = joystick.name();
    found.detail = "opened";
  } catch (const std::exception& e) {
    found.usable = false;
    found.detail = e.what();
  }
  return found;
}

FoundDevice ProbeRobot(const std::string& where, const DiscoveryOptions& options) {
  FoundDevice found{DeviceKind::kRobot, where, "", false, "not probed"};
  robot::RtdeClient::Options rtde;
  const size_t colon = where.rfind(':');
  rtde.host = colon == std::string::npos ? where : where.substr(0, colon);
  if (colon != std::string::npos) {
    try {
      rtde.port = std::stoi(where.substr(colon + 1));
    } catch (const std::exception&) {
      found.detail = "'" + where + "' is not host or host:port";
      return found;
    }
  }
  found.path = rtde.host + ":" + std::to_string(rtde.port);
  if (!options.probe) return found;
  rtde.timeout_s = 1.0;
  try {
    robot::RtdeClient client(rtde);
    found.identity = "UR controller " + client.controller_version().ToString();
    found.detail = client.WaitForData(1.0) ? "RTDE handshake done, state streaming"
                                           : "RTDE handshake done, but no state arrived";
    found.usable = client.connected();
  } catch (const std::exception& e) {
    found.detail = e.what();
  }
  return found;
}

}  // namespace

const char* DeviceKindName(DeviceKind kind) {
  switch (kind) {
    case DeviceKind::kBeacon:
      return "beacon";
    case DeviceKind::kCamera:
      return "camera";
    case DeviceKind::kGamepad:
      return "gamepad";
    case DeviceKind::kRobot:
      return "robot";
  }
  return "?";
}

std::vector<FoundDevice> DiscoverDevices(const DiscoveryOptions& options) {
  std::vector<FoundDevice> found;
  const fs::path dev(options.dev_dir);
  for (const std::string& port : Matching(dev, {"ttyACM", "ttyUSB"})) {
    found.push_back(ProbeBeacon(port, options));
  }
  for (const std::string& path : Matching(dev, {"video"})) {
    found.push_back(ProbeCamera(path, options));
  }
  for (const std::string& path : teleop::LinuxJoystick::Find((dev / "input").string())) {
    found.push_back(ProbeGamepad(path, options));
  }
  for (const std::string& host : options.robot_hosts) found.push_back(ProbeRobot(host, options));
  return found;
}

}  // namespace recon::discovery
