#pragma once

#include <map>
#include <string>
#include <vector>

#include "devices/cell/twin_scene.h"

namespace recon::cell {

/// The devices a digital twin's cell profile points at: a UR controller (robot::FakeUrController
/// or a real one) and the beacons' serial ports (uwb::FakeDwm1001 pseudo-terminals).
struct TwinCellDevices {
  std::string robot_host = "127.0.0.1";
  int rtde_port = 30004;
  int script_port = 30002;
  std::vector<std::string> beacon_ports;
  std::string beacon_mode = "tlv";
  /// Beacon names by node id in hex, as the profile's beacons.names.
  std::map<std::string, std::string> beacon_names;
};

/// Writes a real cell's profile whose camera is a digital twin (TwinCamera) into `folder`:
/// layout.json (`layout`), camera.yaml (the scene's top camera at width x height, no
/// distortion), table_tags.json (the scene's corner tags), and cell.json naming them, the
/// devices and the beacon's tag. Returns cell.json's path. UserError naming a file that cannot be
/// written.
std::string WriteTwinCell(const std::string& folder, const TwinCellDevices& devices,
                          const TwinLayout& layout, int width = 1280, int height = 960);

}  // namespace recon::cell
