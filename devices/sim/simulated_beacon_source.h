#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "devices/uwb/lec_parser.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "engine/devices/beacon_source.h"
#include "engine/devices/clock.h"
#include "engine/worlds/mujoco_model.h"

namespace recon::sim {

/// One simulated UWB tag: a site of the scene (where the tag is) and how its DWM1001 errs,
/// including the hidden table -> UWB pose that calibration must recover.
struct SimulatedBeacon {
  std::string name;  ///< what samples are labelled with, e.g. "plate"
  std::string site;  ///< the MuJoCo site the tag sits at, e.g. "beacon"
  uwb::SimulatedDwm1001Options dwm;
};

/// DWM1001 tags in the simulated cell as a devices::BeaconSource, going through the same bytes and
/// the same parser as a real serial port: every kUpdatePeriod_s of clock time each tag prints one
/// `lec` update (SimulatedDwm1001: a line, nothing, or a garbled line) for its site's current
/// position, which that tag's LecLineParser turns into readings. Each reading with a position
/// becomes a BeaconSample (UWB frame) stamped with the update's time.
///
/// Updates are due at t0 + k * kUpdatePeriod_s (t0: the clock at construction, k = 1, 2, ...), and
/// Poll prints all that are due. The scene's table (world) frame is the tags' table frame; site
/// positions are read as last computed by the physics (mj_forward/mj_step), so updates caught up
/// in one Poll all see the current position: poll at least every control step for the 10 Hz
/// stream to follow motion. After a long pause only the last kMaxBacklogUpdates are printed, as a
/// real tag's serial buffer would have overflowed; the skipped ones are simply missing.
///
/// Holds the scene and the clock by reference; their owner keeps them alive. Not thread-safe.
class SimulatedBeaconSource final : public devices::BeaconSource {
 public:
  static constexpr double kUpdatePeriod_s = 0.1;  ///< the firmware's default 10 Hz
  static constexpr int kMaxBacklogUpdates = 100;

  /// UserError when `beacons` is empty, two share a name, or a site is not in the scene (naming
  /// it and listing the scene's sites).
  SimulatedBeaconSource(const worlds::MujocoModel& scene, std::vector<SimulatedBeacon> beacons,
                        const devices::Clock& clock);

  std::vector<devices::BeaconSample> Poll() override;
  /// The parsers' counters summed over the beacons.
  devices::BeaconSourceStats Stats() const override;
  /// E.g. "simulated DWM1001 beacons: plate at site 'beacon'".
  std::string Describe() const override;

  /// The options of the beacon at `index` (in construction order), e.g. its hidden frame.
  const uwb::SimulatedDwm1001Options& options(int index) const;

 private:
  struct Beacon {
    std::string name;
    std::string site_name;
    int site = -1;
    uwb::SimulatedDwm1001 dwm;
    uwb::LecLineParser parser;
  };

  const worlds::MujocoModel& scene_;
  const devices::Clock& clock_;
  std::vector<Beacon> beacons_;
  double start_s_ = 0.0;
  int64_t updates_done_ = 0;  // k of the last update printed
};

}  // namespace recon::sim
