#include "app/cli/uwb_command.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "devices/uwb/dwm1001_driver.h"
#include "engine/core/error.h"

namespace recon::cli {

namespace {

struct MonitorFlags {
  std::string port;
  int count = 0;         ///< stop after this many readings (0: no limit)
  double seconds = 0.0;  ///< stop after this long (0: no limit)
  bool json = false;
};

void PrintReading(const uwb::TimedReading& r, bool json) {
  const uwb::UwbReading& u = r.reading;
  if (json) {
    nlohmann::json line = {{"t", r.t_s}};
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
    std::printf("%9.3f s  x %7.3f  y %7.3f  z %7.3f m  qf %3d  (%zu anchors)\n", r.t_s, u.x_m,
                u.y_m, u.z_m, u.quality, u.anchors.size());
  } else {
    std::printf("%9.3f s  no position fix  (%zu anchors)\n", r.t_s, u.anchors.size());
  }
  std::fflush(stdout);
}

void RunMonitor(const MonitorFlags& flags) {
  uwb::Dwm1001Driver driver(flags.port);
  std::fprintf(stderr, "recon uwb monitor: streaming from %s (Ctrl-C stops)\n", flags.port.c_str());
  const auto start = std::chrono::steady_clock::now();
  int printed = 0;
  std::vector<uwb::TimedReading> readings;
  bool alive = true;
  while (alive && (flags.count == 0 || printed < flags.count)) {
    if (flags.seconds > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
            flags.seconds) {
      break;
    }
    readings.clear();
    alive = driver.Poll(readings, 50);
    for (const uwb::TimedReading& r : readings) {
      if (flags.count > 0 && printed >= flags.count) break;
      PrintReading(r, flags.json);
      ++printed;
    }
  }
  const uwb::ParseStats& s = driver.stats();
  if (flags.json) {
    std::printf("%s\n", nlohmann::json{{"readings", printed},
                                       {"lines", s.lines},
                                       {"dropped_lines", s.malformed},
                                       {"resynchronised_lines", s.resynced},
                                       {"empty_lines", s.empty}}
                            .dump()
                            .c_str());
  } else {
    std::printf("%d readings; %lld lines, %lld dropped as malformed, %lld resynchronised\n",
                printed, static_cast<long long>(s.lines), static_cast<long long>(s.malformed),
                static_cast<long long>(s.resynced));
  }
  if (!alive) throw UserError(driver.last_error());
}

}  // namespace

void AddUwbCommand(CLI::App& app) {
  CLI::App* uwb = app.add_subcommand("uwb", "UWB beacons (DWM1001) on serial ports");
  uwb->require_subcommand(1);
  auto flags = std::make_shared<MonitorFlags>();
  CLI::App* monitor =
      uwb->add_subcommand("monitor", "print the readings of a DWM1001 tag as they arrive");
  monitor->add_option("--port", flags->port, "serial port, e.g. /dev/ttyACM0")->required();
  monitor->add_option("--count", flags->count, "stop after N readings")
      ->check(CLI::NonNegativeNumber);
  monitor->add_option("--seconds", flags->seconds, "stop after S seconds")
      ->check(CLI::NonNegativeNumber);
  monitor->add_flag("--json", flags->json,
                    "one JSON object per reading (t, x, y, z, qf, anchors), then the counts");
  monitor->callback([flags] { RunMonitor(*flags); });
}

}  // namespace recon::cli
