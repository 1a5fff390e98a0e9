#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace recon::devices {

/// One position update of one beacon, in the UWB (anchor) frame; calibration maps it to the
/// table frame (engine/calib).
struct BeaconSample {
  std::string beacon;  ///< which beacon, e.g. "plate"
  Eigen::Vector3d position_uwb_m = Eigen::Vector3d::Zero();
  int quality = 0;  ///< the location engine's 0-100
  double timestamp_s = 0.0;
};

/// Health counters a status display shows.
struct BeaconSourceStats {
  int64_t lines = 0;      ///< lines received
  int64_t readings = 0;   ///< lines that gave a position
  int64_t malformed = 0;  ///< lines rejected by the parser
};

/// UWB beacons as the workflow sees them: DWM1001 tags on a serial port, or the simulated cell's
/// tags printing the same `lec` lines. Poll returns the samples that arrived since the last call
/// (possibly none); it throws UserError when the device is gone.
class BeaconSource {
 public:
  virtual ~BeaconSource() = default;
  virtual std::vector<BeaconSample> Poll() = 0;
  virtual BeaconSourceStats Stats() const = 0;
  virtual std::string Describe() const = 0;
};

}  // namespace recon::devices
