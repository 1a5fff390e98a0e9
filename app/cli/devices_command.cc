#include "app/cli/devices_command.h"

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli/option_checks.h"
#include "devices/camera/open_camera.h"
#include "devices/discovery/device_discovery.h"

namespace recon::cli {
namespace {

struct ListFlags {
  discovery::DiscoveryOptions options;
  bool no_probe = false;
  bool json = false;
};

void RunList(ListFlags flags) {
  flags.options.probe = !flags.no_probe;
  camera::SilenceOpenCvLogging();
  if (flags.options.probe) {
    std::fprintf(stderr, "recon devices list: probing serial ports, cameras, gamepads%s...\n",
                 flags.options.robot_hosts.empty() ? "" : " and robots");
  }
  const std::vector<discovery::FoundDevice> found = discovery::DiscoverDevices(flags.options);
  if (flags.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& d : found) {
      list.push_back({{"kind", discovery::DeviceKindName(d.kind)},
                      {"path", d.path},
                      {"identity", d.identity},
                      {"usable", d.usable},
                      {"detail", d.detail}});
    }
    std::printf("%s\n",
                nlohmann::json{{"devices", list}, {"probed", flags.options.probe}}.dump(2).c_str());
    return;
  }
  if (found.empty()) {
    std::printf("no beacons, cameras or gamepads in %s%s\n", flags.options.dev_dir.c_str(),
                flags.options.robot_hosts.empty() ? " (robots: pass --robot-host H)" : "");
    return;
  }
  std::printf("%-8s %-22s %-4s %s\n", "kind", "path", "ok", "identity / detail");
  for (const auto& d : found) {
    std::string what = d.identity;
    if (!d.detail.empty()) what += (what.empty() ? "" : " - ") + d.detail;
    std::printf("%-8s %-22s %-4s %s\n", discovery::DeviceKindName(d.kind), d.path.c_str(),
                d.usable ? "yes" : "no", what.c_str());
  }
  if (flags.options.robot_hosts.empty()) {
    std::printf("(robots are on the network: add --robot-host H to look for a UR controller)\n");
  }
}

}  // namespace

void AddDevicesCommand(CLI::App& app) {
  CLI::App* devices = app.add_subcommand("devices", "the hardware connected to this computer");
  devices->require_subcommand(1);
  auto flags = std::make_shared<ListFlags>();
  CLI::App* list = devices->add_subcommand(
      "list", "list UWB beacons (serial ports), cameras, gamepads and UR robots, and probe them");
  list->add_flag("--no-probe", flags->no_probe,
                 "only list device files; do not open them (probing asks each serial port for "
                 "the DWM1001 shell, each camera for a frame, each robot for its RTDE handshake)");
  list->add_option("--robot-host", flags->options.robot_hosts,
                   "a UR controller to try, host or host:port (RTDE, default 30004); repeatable");
  list->add_option("--dev", flags->options.dev_dir, "the device directory")
      ->capture_default_str()
      ->check(CLI::ExistingDirectory);
  list->add_option("--serial-timeout-ms", flags->options.serial_timeout_ms,
                   "how long a serial port may take to answer")
      ->capture_default_str()
      ->check(WholeBetween(1, 600000));
  list->add_flag("--json", flags->json, "a JSON document instead of a table");
  list->callback([flags] { RunList(*flags); });
}

}  // namespace recon::cli
