#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace recon::uwb {

/// A DWM1001 on a pseudo-terminal, for tests, demos and benchmarks: the slave side is a serial
/// port a driver opens like /dev/ttyACM0; the master side answers as the PANS shell does. Two
/// carriage returns enter the shell ("dwm> "), `lec` toggles a 10 Hz stream of the lines
/// `next_update` prints (e.g. SimulatedDwm1001::NextUpdate), `quit` leaves the shell. Unplug()
/// closes the master, which the driver sees as a hang-up.
class FakeDwm1001 {
 public:
  struct Options {
    std::function<std::string()> next_update;  ///< the bytes of one update (may be empty)
    int period_ms = 100;                       ///< the firmware's default rate, 10 Hz
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
  /// Lines streamed so far.
  int64_t updates_sent() const { return updates_sent_; }
  bool streaming() const { return streaming_; }

 private:
  void Run();
  void Handle(char c);
  void Send(const std::string& bytes);

  Options options_;
  int master_ = -1;
  std::string port_;
  std::mutex mutex_;  // guards master_ between Run and Unplug
  std::atomic<bool> stop_{false};
  std::atomic<bool> streaming_{false};
  std::atomic<int64_t> updates_sent_{0};
  bool in_shell_ = false;
  int carriage_returns_ = 0;
  std::string command_;
  std::thread thread_;
};

}  // namespace recon::uwb
