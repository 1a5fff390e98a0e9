#pragma once

#include <string>
#include <vector>

namespace recon {

/// One beacon a teacher sticks on an object: its name (used in file keys, e.g.
/// `obs/beacon_plate`), the object it marks, what it measures and how many numbers it reports.
/// A task's reading b is the beacons' readings concatenated in order.
struct BeaconSpec {
  std::string name;      ///< short identifier: lower case, digits and '_'
  std::string object;    ///< what it is stuck on, for people ("the plate")
  std::string quantity;  ///< "position" or "distance" (from the robot), or a partial reading
  int dim = 0;           ///< numbers per reading
  std::string unit;      ///< "m" for the cell, "px" for the 2-D worlds

  bool operator==(const BeaconSpec& other) const = default;
};

/// The total size of a reading from these beacons.
inline int TotalBeaconDim(const std::vector<BeaconSpec>& beacons) {
  int total = 0;
  for (const BeaconSpec& beacon : beacons) total += beacon.dim;
  return total;
}

}  // namespace recon
