#include "app/cli/uwb_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli/option_checks.h"
#include "devices/uwb/beacon_hub.h"
#include "devices/uwb/fake_dwm1001.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "engine/core/error.h"

namespace recon::cli {

namespace {

struct MonitorFlags {
  std::vector<std::string> ports;
  std::string mode = "lec";
  int fake = 0;                    ///< built-in fake tags instead of ports
  std::vector<std::string> names;  ///< ID=NAME
  int count = 0;                   ///< stop after this many readings (0: no limit)
  double seconds = 0.0;            ///< stop after this long (0: no limit)
  bool json = false;
};

/// Fake tags for a user without hardware (and the demo): each circles its own spot on the table
/// at 10 Hz with the simulated DWM1001's noise, node ids DECA00000000F001, F002, ...
struct FakeCell {
  explicit FakeCell(int n) {
    for (int i = 0; i < n; ++i) {
      uwb::SimulatedDwm1001Options sim;
      sim.seed = static_cast<uint64_t>(i) + 1;
      auto tag = std::make_shared<uwb::SimulatedDwm1001>(sim);
      auto step = std::make_shared<int>(0);
      uwb::FakeDwm1001::Options options;
      options.node_id = 0xDECA00000000F001ull + static_cast<uint64_t>(i);
      const Eigen::Vector2d centre(0.6 + 0.4 * i, 0.9);
      options.next_reading = [tag, step, centre] {
        const double angle = 0.2 * (*step)++;  // a lap every ~3 s at 10 Hz
        return tag->NextReading(Eigen::Vector3d(centre.x() + 0.2 * std::cos(angle),
                                                centre.y() + 0.2 * std::sin(angle), 0.0));
      };
      tags.push_back(std::make_unique<uwb::FakeDwm1001>(options));
    }
  }
  std::vector<std::unique_ptr<uwb::FakeDwm1001>> tags;
};

void PrintReading(const uwb::BeaconReading& r, bool json) {
  const uwb::UwbReading& u = r.reading;
  if (json) {
    nlohmann::json line = {
        {"t", r.t_s}, {"id", uwb::NodeIdHex(r.node_id)}, {"beacon", r.beacon}, {"port", r.port}};
    if (u.has_position) {
      line["x"] = u.x_m;
      line["y"] = u.y_m;
      line["z"] = u.z_m;
      line["qf"] = u.quality;
    }
    nlohmann::json anchors = nlohmann::json::array();
    for (const uwb::AnchorRange& a : u.anchors) {
      char id[8];
      std::snprintf(id, sizeof(id), "%04X", a.id);
      anchors.push_back({{"id", id}, {"distance", a.distance_m}});
    }
    if (!anchors.empty()) line["anchors"] = anchors;
    std::printf("%s\n", line.dump().c_str());
  } else if (u.has_position) {
    std::printf("%-16s %9.3f s  x %7.3f  y %7.3f  z %7.3f m  qf %3d  (%zu anchors)\n",
                r.beacon.c_str(), r.t_s, u.x_m, u.y_m, u.z_m, u.quality, u.anchors.size());
  } else {
    std::printf("%-16s %9.3f s  no position fix  (%zu anchors)\n", r.beacon.c_str(), r.t_s,
                u.anchors.size());
  }
  std::fflush(stdout);
}

void PrintCounts(const uwb::BeaconPortStatus& s, int64_t printed, bool tlv, bool json) {
  const std::string id = s.node_id != 0 ? uwb::NodeIdHex(s.node_id) : "";
  if (json) {
    nlohmann::json line = {
        {"port", s.port}, {"id", id}, {"beacon", s.beacon}, {"readings", printed}};
    if (tlv) {
      line["responses"] = s.updates;
      line["malformed_responses"] = s.malformed;
      line["dropped_bytes"] = s.tlv_stats.dropped_bytes;
    } else {
      line["lines"] = s.lec_stats.lines;
      line["dropped_lines"] = s.lec_stats.malformed;
      line["resynchronised_lines"] = s.lec_stats.resynced;
      line["empty_lines"] = s.lec_stats.empty;
    }
    std::printf("%s\n", line.dump().c_str());
  } else if (tlv) {
    std::printf("%s (%s): %lld readings; %lld responses, %lld malformed, %lld bytes dropped\n",
                s.port.c_str(), id.c_str(), static_cast<long long>(printed),
                static_cast<long long>(s.updates), static_cast<long long>(s.malformed),
                static_cast<long long>(s.tlv_stats.dropped_bytes));
  } else {
    std::printf(
        "%s (%s): %lld readings; %lld lines, %lld dropped as malformed, %lld "
        "resynchronised\n",
        s.port.c_str(), id.c_str(), static_cast<long long>(printed),
        static_cast<long long>(s.lec_stats.lines), static_cast<long long>(s.lec_stats.malformed),
        static_cast<long long>(s.lec_stats.resynced));
  }
}

uwb::BeaconHubOptions HubOptions(const MonitorFlags& flags, const FakeCell& fakes) {
  uwb::BeaconHubOptions options;
  options.ports = flags.ports;
  for (const auto& tag : fakes.tags) options.ports.push_back(tag->port());
  if (options.ports.empty()) {
    throw UserError(
        "give the beacons' serial ports with --port PATH (once per beacon), or "
        "--fake N to try the monitor without hardware");
  }
  options.driver.mode = uwb::ParseDwm1001Mode(flags.mode);
  for (const std::string& pair : flags.names) {
    const size_t eq = pair.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == pair.size()) {
      throw UserError("--name " + pair + ": expected NODE_ID=NAME, e.g. DECA0000000012AB=plate");
    }
    options.names[pair.substr(0, eq)] = pair.substr(eq + 1);
  }
  return options;
}

void RunMonitor(const MonitorFlags& flags) {
  const FakeCell fakes(flags.fake);
  const uwb::BeaconHubOptions options = HubOptions(flags, fakes);
  const bool tlv = options.driver.mode == uwb::Dwm1001Mode::kTlvPolling;
  uwb::BeaconHub hub(options);
  // At start a port that does not work is the user's to fix now; later, unplugs are retried.
  for (const uwb::BeaconPortStatus& s : hub.Status()) {
    if (!s.connected) throw UserError(s.last_error);
  }
  std::fprintf(stderr, "recon uwb monitor: %s (Ctrl-C stops)\n", hub.Describe().c_str());
  const auto start = std::chrono::steady_clock::now();
  int printed = 0;
  std::map<std::string, int64_t> printed_by_port;
  std::vector<uwb::BeaconPortStatus> before = hub.Status();
  while (flags.count == 0 || printed < flags.count) {
    if (flags.seconds > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
            flags.seconds) {
      break;
    }
    for (const uwb::BeaconReading& r : hub.PollReadings(50)) {
      if (flags.count > 0 && printed >= flags.count) break;
      PrintReading(r, flags.json);
      ++printed;
      ++printed_by_port[r.port];
    }
    const std::vector<uwb::BeaconPortStatus> now = hub.Status();
    for (size_t i = 0; i < now.size(); ++i) {
      if (before[i].connected && !now[i].connected) {
        std::fprintf(stderr, "recon uwb monitor: %s lost: %s; retrying every %g s\n",
                     now[i].port.c_str(), now[i].last_error.c_str(), options.retry_period_s);
      } else if (!before[i].connected && now[i].connected) {
        std::fprintf(stderr, "recon uwb monitor: %s is back (%s)\n", now[i].port.c_str(),
                     now[i].beacon.c_str());
      }
    }
    before = now;
    if (hub.connected_count() == 0) break;  // nothing left to monitor
  }
  for (const uwb::BeaconPortStatus& s : hub.Status()) {
    PrintCounts(s, printed_by_port[s.port], tlv, flags.json);
  }
  if (hub.connected_count() == 0) throw UserError(hub.Status().front().last_error);
}

}  // namespace

void AddUwbCommand(CLI::App& app) {
  CLI::App* uwb = app.add_subcommand("uwb", "UWB beacons (DWM1001) on serial ports");
  uwb->require_subcommand(1);
  auto flags = std::make_shared<MonitorFlags>();
  CLI::App* monitor =
      uwb->add_subcommand("monitor", "print the readings of DWM1001 tags as they arrive");
  monitor->add_option("--port", flags->ports,
                      "serial port of a tag, e.g. /dev/ttyACM0; repeat for several tags");
  monitor
      ->add_option("--mode", flags->mode,
                   "lec: stream lines from the PANS shell; tlv: poll loc_get in binary mode")
      ->check(CLI::IsMember({"lec", "tlv"}));
  monitor->add_option("--fake", flags->fake, "also run N built-in fake tags on pseudo-terminals")
      ->check(WholeBetween(0, 8));
  monitor->add_option("--name", flags->names,
                      "NODE_ID=NAME: name a tag by its node id (as `si` prints it), repeatable");
  monitor->add_option("--count", flags->count, "stop after N readings")->check(NonNegativeWhole());
  monitor->add_option("--seconds", flags->seconds, "stop after S seconds")
      ->check(NumberBetween(0, kMaxWaitSeconds));
  monitor->add_flag("--json", flags->json,
                    "one JSON object per reading (t, id, beacon, port, x, y, z, qf, anchors), "
                    "then the counts of each port");
  monitor->callback([flags] { RunMonitor(*flags); });
}

}  // namespace recon::cli
