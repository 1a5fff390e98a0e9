#include "devices/uwb/beacon_hub.h"

#include <poll.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <exception>
#include <set>

#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::uwb {

namespace {

// "DECA0000000012AB", "0xdeca...", "12ab": 1-16 hex digits.
uint64_t ParseNodeIdKey(const std::string& key) {
  std::string_view digits = key;
  if (digits.substr(0, 2) == "0x" || digits.substr(0, 2) == "0X") digits.remove_prefix(2);
  uint64_t id = 0;
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, id, 16);
  if (digits.empty() || digits.size() > 16 || ec != std::errc() || ptr != end) {
    throw UserError("beacon name for \"" + key +
                    "\": the key must be a node id in hex, as `si` prints it after addr=x "
                    "(e.g. DECA0000000012AB)");
  }
  return id;
}

}  // namespace

struct BeaconHub::Port {
  BeaconPortStatus status;
  std::unique_ptr<Dwm1001Driver> driver;
  double next_retry_s = 0;
};

BeaconHub::BeaconHub(BeaconHubOptions options)
    : options_(std::move(options)), epoch_s_(SteadySeconds()) {
  if (options_.ports.empty()) throw UserError("no beacon port given");
  std::set<std::string> seen;
  for (const std::string& port : options_.ports) {
    if (!seen.insert(port).second) throw UserError("beacon port " + port + " given twice");
  }
  for (const auto& [key, name] : options_.names) names_by_id_[ParseNodeIdKey(key)] = name;
  for (const std::string& path : options_.ports) {
    auto port = std::make_unique<Port>();
    port->status.port = path;
    ports_.push_back(std::move(port));
  }
  // First attempt now, for every port; failures are retried like unplugs.
  for (auto& port : ports_) {
    try {
      port->driver = std::make_unique<Dwm1001Driver>(port->status.port, options_.driver);
      Connected(*port);
    } catch (const std::exception& e) {
      port->status.last_error = e.what();
      port->next_retry_s = SteadySeconds() + options_.retry_period_s;
    }
  }
}

BeaconHub::~BeaconHub() = default;

std::string BeaconHub::BeaconName(uint64_t node_id,
                                  const std::map<uint64_t, std::string>& names_by_id) {
  const auto it = names_by_id.find(node_id);
  return it != names_by_id.end() ? it->second : NodeIdHex(node_id);
}

void BeaconHub::Connected(Port& port) {
  port.status.connected = true;
  port.status.last_error.clear();
  port.status.node_id = port.driver->node_id();
  port.status.beacon = BeaconName(port.status.node_id, names_by_id_);
}

void BeaconHub::RetryDue(double now_s) {
  for (auto& port : ports_) {
    if (port->status.connected || now_s < port->next_retry_s) continue;
    try {
      if (port->driver) {
        port->driver->Reconnect();
      } else {
        port->driver = std::make_unique<Dwm1001Driver>(port->status.port, options_.driver);
      }
      Connected(*port);
      ++port->status.reconnects;
    } catch (const std::exception& e) {
      // Whatever went wrong (missing node, busy port, no answer), the other tags go on.
      port->status.last_error = e.what();
      port->next_retry_s = SteadySeconds() + options_.retry_period_s;
    }
  }
}

void BeaconHub::PollPort(Port& port, int timeout_ms, std::vector<BeaconReading>& out) {
  if (!port.status.connected) return;
  std::vector<TimedReading> readings;
  const bool alive = port.driver->Poll(readings, timeout_ms);
  const double offset_s = port.driver->epoch_s() - epoch_s_;
  for (TimedReading& r : readings) {
    out.push_back({port.status.beacon, port.status.port, port.status.node_id, offset_s + r.t_s,
                   std::move(r.reading)});
  }
  const Dwm1001Counts counts = port.driver->counts();
  port.status.updates = counts.updates;
  port.status.readings = counts.readings;
  port.status.malformed = counts.malformed;
  port.status.lec_stats = port.driver->stats();
  port.status.tlv_stats = port.driver->tlv_stats();
  if (!alive) {
    port.status.connected = false;
    port.status.last_error = port.driver->last_error();
    port.next_retry_s = SteadySeconds() + options_.retry_period_s;
  }
}

std::vector<BeaconReading> BeaconHub::PollReadings(int timeout_ms) {
  std::vector<BeaconReading> out;
  const double deadline_s = SteadySeconds() + timeout_ms / 1000.0;
  while (true) {
    RetryDue(SteadySeconds());
    for (auto& port : ports_) PollPort(*port, 0, out);
    const double left_s = deadline_s - SteadySeconds();
    if (!out.empty() || left_s <= 0) return out;
    // Wait on every connected port at once; wake at least every 10 ms, so TLV requests and
    // reconnection attempts stay on time.
    std::vector<pollfd> fds;
    for (const auto& port : ports_) {
      if (port->status.connected && port->driver->fd() >= 0) {
        fds.push_back({port->driver->fd(), POLLIN, 0});
      }
    }
    const int wait_ms = std::clamp(static_cast<int>(left_s * 1000.0), 0, 10);
    ::poll(fds.data(), fds.size(), wait_ms);
  }
}

std::vector<devices::BeaconSample> BeaconHub::Poll() {
  std::vector<devices::BeaconSample> samples;
  for (BeaconReading& r : PollReadings(0)) {
    if (!r.reading.has_position) continue;
    samples.push_back({std::move(r.beacon),
                       Eigen::Vector3d(r.reading.x_m, r.reading.y_m, r.reading.z_m),
                       r.reading.quality, r.t_s});
  }
  return samples;
}

devices::BeaconSourceStats BeaconHub::Stats() const {
  devices::BeaconSourceStats stats;
  for (const auto& port : ports_) {
    stats.lines += port->status.updates;
    stats.readings += port->status.readings;
    stats.malformed += port->status.malformed;
  }
  return stats;
}

std::string BeaconHub::Describe() const {
  std::string out =
      "DWM1001 beacons (" + std::string(Dwm1001ModeName(options_.driver.mode)) + " mode):";
  for (const auto& port : ports_) {
    const BeaconPortStatus& s = port->status;
    out += (port == ports_.front() ? " " : ", ") + (s.beacon.empty() ? "?" : s.beacon) + " on " +
           s.port + (s.connected ? " (connected)" : " (reconnecting: " + s.last_error + ")");
  }
  return out;
}

std::vector<BeaconPortStatus> BeaconHub::Status() const {
  std::vector<BeaconPortStatus> out;
  for (const auto& port : ports_) out.push_back(port->status);
  return out;
}

int BeaconHub::connected_count() const {
  return static_cast<int>(std::count_if(ports_.begin(), ports_.end(),
                                        [](const auto& port) { return port->status.connected; }));
}

}  // namespace recon::uwb
