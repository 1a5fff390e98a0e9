#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/uwb/lec_parser.h"
#include "devices/uwb/serial_port.h"
#include "devices/uwb/tlv_codec.h"
#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

/// A reading with the host's time of arrival (steady clock, seconds since the driver started).
struct TimedReading {
  double t_s = 0;
  UwbReading reading;
};

/// How the driver talks to the tag.
enum class Dwm1001Mode {
  /// Enter the PANS shell and stream `lec` lines (the tag pushes each update).
  kLecShell,
  /// Stay in binary TLV mode, set the update rate with upd_rate_set and poll loc_get at it.
  kTlvPolling,
};

/// Parses "lec" / "tlv" (as `recon uwb monitor --mode` takes it); UserError otherwise.
Dwm1001Mode ParseDwm1001Mode(const std::string& text);
const char* Dwm1001ModeName(Dwm1001Mode mode);

/// The 16 upper-case hex digits of a node id, e.g. "DECA0000000012AB".
std::string NodeIdHex(uint64_t node_id);

struct Dwm1001Options {
  Dwm1001Mode mode = Dwm1001Mode::kLecShell;
  /// How long the tag may take to answer at start (shell prompt, `si`, node_id_get).
  int answer_timeout_ms = 2000;
  /// TLV mode: the update period set with upd_rate_set (rounded to 100 ms units, at least one)
  /// and the loc_get polling period. The `lec` stream keeps the tag's own rate.
  int update_period_ms = 100;
};

/// Health counters common to both modes, for status displays.
struct Dwm1001Counts {
  int64_t updates = 0;    ///< lec lines, or TLV responses (status frames)
  int64_t readings = 0;   ///< readings delivered
  int64_t malformed = 0;  ///< lec: rejected lines; TLV: error statuses and garbled stretches
};

/// A DWM1001 tag on a serial port. In kLecShell mode it enters the PANS shell (two carriage
/// returns), reads the node id with `si`, starts the `lec` stream and parses what arrives,
/// tolerating garbled and interleaved lines (LecLineParser) and partial reads. In kTlvPolling
/// mode it reads the node id with node_id_get, sets the rate with upd_rate_set and polls loc_get,
/// parsing the binary responses (TlvResponseParser). Readings are timestamped on arrival. An
/// unplugged tag is reported by Poll returning false; Reconnect() opens the port again and
/// restarts. Not thread-safe.
class Dwm1001Driver {
 public:
  /// Opens `port` and starts. UserError naming the port when it cannot be opened or no DWM1001
  /// answers within the answer timeout (with the bytes that did arrive).
  explicit Dwm1001Driver(std::string port, int answer_timeout_ms = 2000);
  Dwm1001Driver(std::string port, Dwm1001Options options);
  ~Dwm1001Driver();
  Dwm1001Driver(const Dwm1001Driver&) = delete;
  Dwm1001Driver& operator=(const Dwm1001Driver&) = delete;

  /// Waits up to `timeout_ms` for data (sending loc_get when it is due) and appends the readings
  /// parsed from it. False once the tag is gone, with the reason in last_error().
  bool Poll(std::vector<TimedReading>& out, int timeout_ms);
  /// Opens the port again after an unplug and reads the node id again; UserError as the
  /// constructor. The parser counters continue.
  void Reconnect();

  /// The tag's 64-bit node id, read at start; the anchors know it by its low 16 bits.
  uint64_t node_id() const { return node_id_; }
  Dwm1001Mode mode() const { return options_.mode; }
  const ParseStats& stats() const { return parser_.stats(); }
  const TlvParseStats& tlv_stats() const { return tlv_parser_.stats(); }
  Dwm1001Counts counts() const;
  const std::string& port() const { return port_; }
  bool connected() const { return serial_ && serial_->open(); }
  const std::string& last_error() const { return last_error_; }
  /// The port's file descriptor, to wait on several tags at once with poll(2); -1 if closed.
  int fd() const { return connected() ? serial_->fd() : -1; }
  /// Steady-clock seconds (since the clock's epoch) at which t_s = 0.
  double epoch_s() const { return started_; }

 private:
  void Start();
  void StartShell();
  void StartTlv();
  // Sends `request` and reads until `frames` holds a frame of `kind` (or the deadline).
  std::optional<TlvFrame> TlvExchange(const std::string& request, TlvFrame::Kind kind,
                                      int timeout_ms, std::string& received);
  void HandleFrames(std::vector<TlvFrame>& frames, double now, std::vector<TimedReading>& out);
  double Now() const;

  std::string port_;
  Dwm1001Options options_;
  std::unique_ptr<SerialPort> serial_;
  LecLineParser parser_;
  TlvResponseParser tlv_parser_;
  std::optional<UwbReading> pending_;  // TLV: a position waiting for its anchor list
  double next_request_s_ = 0;          // TLV: when the next loc_get is due (steady seconds)
  int64_t tlv_readings_ = 0;
  uint64_t node_id_ = 0;
  std::string last_error_;
  double started_ = 0;
};

}  // namespace recon::uwb
