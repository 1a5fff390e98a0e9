#pragma once

#include <memory>
#include <string>
#include <vector>

#include "devices/uwb/lec_parser.h"
#include "devices/uwb/serial_port.h"
#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

/// A reading with the host's time of arrival (steady clock, seconds since the driver started).
struct TimedReading {
  double t_s = 0;
  UwbReading reading;
};

/// A DWM1001 tag on a serial port, streaming `lec` lines: enters the PANS shell (two carriage
/// returns), starts the stream, and parses what arrives into timestamped readings, tolerating
/// garbled and interleaved lines (LecLineParser) and partial reads. An unplugged tag is
/// reported by Poll returning false; Reconnect() opens the port again and restarts the stream.
class Dwm1001Driver {
 public:
  /// Opens `port` and starts the stream. UserError naming the port when it cannot be opened or
  /// no DWM1001 shell answers within `answer_timeout_ms` (with the bytes that did arrive).
  explicit Dwm1001Driver(std::string port, int answer_timeout_ms = 2000);
  ~Dwm1001Driver();

  /// Waits up to `timeout_ms` for data and appends the readings parsed from it. False once the
  /// tag is gone, with the reason in last_error().
  bool Poll(std::vector<TimedReading>& out, int timeout_ms);
  /// Opens the port again after an unplug; UserError as the constructor.
  void Reconnect();

  const ParseStats& stats() const { return parser_.stats(); }
  const std::string& port() const { return port_; }
  bool connected() const { return serial_ && serial_->open(); }
  const std::string& last_error() const { return last_error_; }

 private:
  void Start();
  double Now() const;

  std::string port_;
  int answer_timeout_ms_;
  std::unique_ptr<SerialPort> serial_;
  LecLineParser parser_;
  std::string last_error_;
  double started_ = 0;
};

}  // namespace recon::uwb
