#include "devices/sim/simulated_beacon_source.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

#include "devices/sim/scene_lookup.h"
#include "engine/core/error.h"

namespace recon::sim {

namespace {

// Clock times are sums of control periods (0.1 + 0.1 + ... is not exactly k * 0.1): an update is
// due when the clock is within this of its time, so ten 0.1 s steps give ten updates, not nine.
constexpr double kDueTolerance_s = 1e-9;

}  // namespace

SimulatedBeaconSource::SimulatedBeaconSource(const worlds::MujocoModel& scene,
                                             std::vector<SimulatedBeacon> beacons,
                                             const devices::Clock& clock)
    : scene_(scene), clock_(clock), start_s_(clock.NowSeconds()) {
  if (beacons.empty()) throw UserError("a simulated beacon source needs at least one beacon");
  std::set<std::string> names;
  beacons_.reserve(beacons.size());
  for (SimulatedBeacon& beacon : beacons) {
    if (!names.insert(beacon.name).second) {
      throw UserError("two simulated beacons are named '" + beacon.name + "'");
    }
    const int site = FindSite(scene_, beacon.site, "simulated beacon '" + beacon.name + "'");
    beacons_.push_back(Beacon{beacon.name, beacon.site, site,
                              uwb::SimulatedDwm1001(std::move(beacon.dwm)), uwb::LecLineParser()});
  }
}

std::vector<devices::BeaconSample> SimulatedBeaconSource::Poll() {
  const double elapsed_s = clock_.NowSeconds() - start_s_;
  const auto due =
      static_cast<int64_t>(std::floor((elapsed_s + kDueTolerance_s) / kUpdatePeriod_s));
  if (due - updates_done_ > kMaxBacklogUpdates) updates_done_ = due - kMaxBacklogUpdates;

  std::vector<devices::BeaconSample> samples;
  std::vector<uwb::UwbReading> readings;
  const mjtNum* site_xpos = scene_.data()->site_xpos;
  for (int64_t k = updates_done_ + 1; k <= due; ++k) {
    const double update_s = start_s_ + static_cast<double>(k) * kUpdatePeriod_s;
    for (Beacon& beacon : beacons_) {
      const mjtNum* p = site_xpos + 3 * beacon.site;
      readings.clear();
      beacon.parser.Feed(beacon.dwm.NextUpdate(Eigen::Vector3d(p[0], p[1], p[2])), readings);
      for (const uwb::UwbReading& r : readings) {
        // A DIST line without a fix ranges the anchors but places nothing.
        if (!r.has_position) continue;
        devices::BeaconSample sample;
        sample.beacon = beacon.name;
        sample.position_uwb_m = Eigen::Vector3d(r.x_m, r.y_m, r.z_m);
        sample.quality = r.quality;
        sample.timestamp_s = update_s;
        samples.push_back(std::move(sample));
      }
    }
  }
  updates_done_ = std::max(updates_done_, due);
  return samples;
}

devices::BeaconSourceStats SimulatedBeaconSource::Stats() const {
  devices::BeaconSourceStats stats;
  for (const Beacon& beacon : beacons_) {
    stats.lines += beacon.parser.stats().lines;
    stats.readings += beacon.parser.stats().readings;
    stats.malformed += beacon.parser.stats().malformed;
  }
  return stats;
}

std::string SimulatedBeaconSource::Describe() const {
  std::string out = "simulated DWM1001 beacons:";
  for (size_t i = 0; i < beacons_.size(); ++i) {
    out += (i == 0 ? " " : ", ") + beacons_[i].name + " at site '" + beacons_[i].site_name + "'";
  }
  return out;
}

const uwb::SimulatedDwm1001Options& SimulatedBeaconSource::options(int index) const {
  return beacons_.at(static_cast<size_t>(index)).dwm.options();
}

}  // namespace recon::sim
