#pragma once

#include <string>
#include <string_view>

namespace recon::uwb {

/// A serial port in raw mode, 115200 8N1 by default (a DWM1001's USB CDC-ACM port, or a
/// pseudo-terminal in tests). Reads wait at most a given time; an unplugged device is reported
/// by Read returning false with the reason, never by a crash or a hang.
class SerialPort {
 public:
  /// Opens and configures `path`. UserError naming the path and the reason (missing, busy, no
  /// permission: "add yourself to the dialout group").
  explicit SerialPort(const std::string& path, int baud = 115200);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Appends what arrives within `timeout_ms` to `out` (nothing is fine). False once the device
  /// is gone (hung up, unplugged), with the reason in last_error().
  bool Read(std::string& out, int timeout_ms);
  /// Writes all of `bytes`; false (with last_error()) if the device is gone.
  bool Write(std::string_view bytes);

  const std::string& path() const { return path_; }
  bool open() const { return fd_ >= 0; }
  /// The file descriptor, to wait on several ports with poll(2); -1 when closed. Do not read it.
  int fd() const { return fd_; }
  const std::string& last_error() const { return last_error_; }

 private:
  void Fail(const std::string& why);

  std::string path_;
  int fd_ = -1;
  std::string last_error_;
};

}  // namespace recon::uwb
