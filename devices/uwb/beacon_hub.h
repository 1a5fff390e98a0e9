#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "devices/uwb/dwm1001_driver.h"
#include "devices/uwb/uwb_reading.h"
#include "engine/devices/beacon_source.h"

namespace recon::uwb {

/// What a BeaconHub is asked to run.
struct BeaconHubOptions {
  /// One DWM1001 tag per serial port. Prefer stable udev paths (/dev/serial/by-id/...): a tag
  /// that is unplugged and plugged back in may come back as another /dev/ttyACM*.
  std::vector<std::string> ports;
  /// Beacon names by node id: key = the node id in hex as `si` prints it (e.g.
  /// "DECA0000000012AB"; case, leading zeros and a "0x" prefix do not matter), value = the name
  /// the workflow uses (e.g. "plate"). A tag whose id is not listed is named by NodeIdHex.
  std::map<std::string, std::string> names;
  Dwm1001Options driver;        ///< mode, answer timeout and update period for every tag
  double retry_period_s = 1.0;  ///< how often a missing tag is tried again
};

/// The health of one port, for `recon devices list` and the studio's status line.
struct BeaconPortStatus {
  std::string port;
  std::string beacon;    ///< its name; empty until the tag has answered once
  uint64_t node_id = 0;  ///< 0 until the tag has answered once
  bool connected = false;
  /// Why the port is not connected (open failure, hang-up, no answer); empty when connected.
  std::string last_error;
  int64_t updates = 0;      ///< lec lines or TLV responses received
  int64_t readings = 0;     ///< readings delivered
  int64_t malformed = 0;    ///< lines or responses rejected
  int reconnects = 0;       ///< successful reconnections after an unplug or a failed start
  ParseStats lec_stats;     ///< the parser's counters in kLecShell mode
  TlvParseStats tlv_stats;  ///< the parser's counters in kTlvPolling mode
};

/// One reading with where it came from.
struct BeaconReading {
  std::string beacon;  ///< the name (BeaconHubOptions::names, else the node id in hex)
  std::string port;
  uint64_t node_id = 0;
  double t_s = 0.0;  ///< arrival time, steady clock, seconds since the hub was created
  UwbReading reading;
};

/// Several DWM1001 tags, one Dwm1001Driver per port, seen as one BeaconSource. Each tag is named
/// by its node id through the user's map, so the names follow the tags whichever port they are
/// on. A port that cannot be opened at start, or that hangs up later, is reported in Status()
/// and tried again every retry_period_s while the other tags keep streaming; nothing here throws
/// once constructed. A reconnection attempt blocks for up to the driver's answer timeout when a
/// port exists but does not answer. Not thread-safe: poll from one thread.
class BeaconHub : public devices::BeaconSource {
 public:
  /// Starts every port it can. UserError only for options that can never work: no port, a
  /// port given twice, a names key that is not a hex node id.
  explicit BeaconHub(BeaconHubOptions options);
  ~BeaconHub() override;

  /// Waits up to `timeout_ms` for readings from any tag (returning as soon as some arrive),
  /// retrying missing tags when due.
  std::vector<BeaconReading> PollReadings(int timeout_ms);

  /// devices::BeaconSource: the position readings that arrived since the last call, without
  /// waiting. Never throws: an unplugged tag shows in Status() and Describe().
  std::vector<devices::BeaconSample> Poll() override;
  /// Sums over all ports.
  devices::BeaconSourceStats Stats() const override;
  /// One line: each beacon with its port and state, e.g.
  /// "DWM1001 beacons: plate on /dev/ttyACM0 (connected), DECA...02 on /dev/ttyACM1 (...)".
  std::string Describe() const override;

  /// One entry per port, in the order of BeaconHubOptions::ports.
  std::vector<BeaconPortStatus> Status() const;
  int connected_count() const;

  /// The name of a node id under `names` (see BeaconHubOptions::names).
  static std::string BeaconName(uint64_t node_id,
                                const std::map<uint64_t, std::string>& names_by_id);

 private:
  struct Port;

  void RetryDue(double now_s);
  void Connected(Port& port);
  void PollPort(Port& port, int timeout_ms, std::vector<BeaconReading>& out);

  BeaconHubOptions options_;
  std::map<uint64_t, std::string> names_by_id_;
  std::vector<std::unique_ptr<Port>> ports_;
  double epoch_s_ = 0;
};

}  // namespace recon::uwb
