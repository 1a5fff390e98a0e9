#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "devices/uwb/uwb_reading.h"
#include "engine/calib/rigid_fit.h"
#include "engine/core/rng.h"

namespace recon::uwb {

/// How the simulated DWM1001 tag errs. Defaults follow REFERENCE.md section 4: about 10 cm of
/// position error, and at high rates an occasional lost or garbled line.
struct SimulatedDwm1001Options {
  /// Anchors at known positions in the UWB (anchor) frame, metres.
  std::vector<Eigen::Vector3d> anchors_m = {
      {0.0, 0.0, 1.2}, {2.4, 0.0, 1.2}, {2.4, 1.8, 1.2}, {0.0, 1.8, 1.2}};
  std::vector<uint16_t> anchor_ids = {0x0C8A, 0x1D42, 0x2F2F, 0xDCAE};
  double position_noise_m = 0.07;    ///< per axis; about 10 cm in the plane
  double range_noise_m = 0.05;       ///< per anchor range
  double drop_probability = 0.02;    ///< an update prints nothing
  double garble_probability = 0.03;  ///< an update prints a corrupted line
  /// The hidden pose of the table frame in the UWB frame: p_uwb = table_to_uwb.Apply(p_table).
  /// Calibration must recover its inverse.
  calib::RigidTransform table_to_uwb;
  uint64_t seed = 1;
};

/// A simulated DWM1001 tag in `lec` streaming mode: for each update it prints what the real
/// firmware would print for a beacon at a given table position, so the simulated cell feeds the
/// same parser and calibration as a real serial port.
class SimulatedDwm1001 {
 public:
  explicit SimulatedDwm1001(SimulatedDwm1001Options options);

  /// The bytes of one 10 Hz update for a beacon at `table_position_m`: a `DIST,...,POS,...`
  /// line, nothing (dropped), or a garbled line (an echo fragment glued to it, or a cut line).
  std::string NextUpdate(const Eigen::Vector3d& table_position_m);
  /// The location engine's result for a beacon at `table_position_m`, with the configured noise
  /// but never dropped or garbled: what TLV loc_get reports (FakeDwm1001::Options::next_reading).
  UwbReading NextReading(const Eigen::Vector3d& table_position_m);

  int64_t dropped() const { return dropped_; }
  int64_t garbled() const { return garbled_; }
  const SimulatedDwm1001Options& options() const { return options_; }

 private:
  SimulatedDwm1001Options options_;
  Rng rng_;
  int64_t dropped_ = 0;
  int64_t garbled_ = 0;
};

}  // namespace recon::uwb
