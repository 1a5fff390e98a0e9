#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "engine/calib/rigid_fit.h"
#include "engine/core/rng.h"

namespace recon::uwb {
class FakeDwm1001;
}

namespace recon::cell {

/// How a TwinBeacon reports.
struct TwinBeaconOptions {
  uint64_t node_id = 0xDECA0000000000A1ull;
  /// The installation's UWB frame: where the anchors measure a table point (the hidden frame a
  /// calibration must recover).
  calib::RigidTransform table_to_uwb;
  /// Uniform noise on x and y of each reading, metres (a DWM1001 scatters a few centimetres).
  double noise_m = 0.02;
  uint64_t seed = 1;  ///< of the noise
  int period_ms = 100;
};

/// A digital twin's beacon: a uwb::FakeDwm1001 on a pseudo-terminal (in `lec` mode a driver
/// reads its lines) that reports the table point it was last moved to (the beacon beside the
/// twin's plate, TwinScene::BeaconPosition), as the anchors measure it. Silenced, it prints
/// lines without a position, as a tag without a fix does. Thread-safe.
class TwinBeacon {
 public:
  TwinBeacon(const Eigen::Vector3d& table_m, TwinBeaconOptions options);
  ~TwinBeacon();  // stops the fake first: its thread reads this object
  TwinBeacon(const TwinBeacon&) = delete;
  TwinBeacon& operator=(const TwinBeacon&) = delete;

  void MoveTo(const Eigen::Vector3d& table_m);
  void Silence(bool silent);
  /// The serial port to open, e.g. /dev/pts/7.
  const std::string& port() const;
  const TwinBeaconOptions& options() const { return options_; }

 private:
  TwinBeaconOptions options_;
  std::mutex mutex_;
  Eigen::Vector3d table_m_;
  bool silent_ = false;
  Rng noise_;
  std::unique_ptr<uwb::FakeDwm1001> fake_;
};

}  // namespace recon::cell
