#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

/// A DWM1001 on a pseudo-terminal, for tests, demos and benchmarks: the slave side is a serial
/// port a driver opens like /dev/ttyACM0; the master side answers as the PANS firmware does. It
/// starts in binary TLV mode, as the firmware boots: pos_get, loc_get, upd_rate_set and
/// node_id_get get their real responses, an unknown type or a stray byte gets 0x40 0x01 0x01.
/// Two carriage returns enter the shell ("dwm> "): `lec` toggles a stream of one line per update,
/// `si` prints the system info with the node address, `quit` returns to TLV mode. Unplug()
/// closes the master, which the driver sees as a hang-up.
class FakeDwm1001 {
 public:
  struct Options {
    /// The bytes of one `lec` update, called only while streaming (may be empty, or scripted
    /// garbage). When unset, the stream prints FormatLecLine(next_reading()).
    std::function<std::string()> next_update;
    int period_ms = 100;  ///< the firmware's default rate, 10 Hz; upd_rate_set changes it
    /// The location engine's result at each update, in every mode: what TLV loc_get/pos_get
    /// answer (nothing yet: no fix) and, without next_update, what the `lec` stream prints.
    std::function<UwbReading()> next_reading = nullptr;
    uint64_t node_id = 0xDECA000000000001;  ///< what `si` and node_id_get report
  };
  /// Opens the pseudo-terminal pair and starts answering. UserError if the system has no ptys.
  explicit FakeDwm1001(Options options);
  ~FakeDwm1001();
  FakeDwm1001(const FakeDwm1001&) = delete;
  FakeDwm1001& operator=(const FakeDwm1001&) = delete;

  /// The port to open, e.g. /dev/pts/7.
  const std::string& port() const { return port_; }
  /// The device disappears (its master side closes).
  void Unplug();
  /// Updates streamed so far (lec lines).
  int64_t updates_sent() const { return updates_sent_; }
  bool streaming() const { return streaming_; }
  bool in_shell() const { return in_shell_; }
  /// TLV requests answered (including the ones answered with an error).
  int64_t tlv_requests() const { return tlv_requests_; }
  /// The current update period, as upd_rate_set left it.
  int period_ms() const { return period_ms_; }

 private:
  using Clock = std::chrono::steady_clock;

  void Run();
  void Handle(char c);
  void HandleShellCommand(const std::string& command);
  void HandleTlvByte(char c);
  void AnswerTlv();
  void ExpireTlvRequest();
  void Update();
  void Send(const std::string& bytes);

  Options options_;
  int master_ = -1;
  std::string port_;
  std::mutex mutex_;  // guards master_ between Run and Unplug
  std::atomic<bool> stop_{false};
  std::atomic<bool> streaming_{false};
  std::atomic<bool> in_shell_{false};
  std::atomic<int64_t> updates_sent_{0};
  std::atomic<int64_t> tlv_requests_{0};
  std::atomic<int> period_ms_;
  // Only the Run thread touches the rest.
  UwbReading current_;  // the latest location-engine result
  std::string command_;
  std::string request_;      // an incomplete TLV request
  bool pending_cr_ = false;  // a '\r' that may be the first of the two that open the shell
  Clock::time_point last_request_byte_;
  std::thread thread_;
};

}  // namespace recon::uwb
