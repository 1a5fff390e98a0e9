#pragma once

#include <array>
#include <mutex>
#include <string>

#include "devices/robot/tcp_socket.h"

namespace recon::robot {

/// A UR controller's script port (30002, the primary interface): each line sent is a URScript
/// program that replaces the one running, which is how a new speedj takes over from the last.
/// The controller also streams state packets on this port; they are read and dropped so its
/// send buffer never fills, and reading them is how a hang-up is noticed between commands.
/// Thread-safe: commands from several threads go out as whole lines.
class UrScriptClient {
 public:
  /// Connects within `timeout_s`; UserError naming host:port when it cannot.
  UrScriptClient(const std::string& host, int port = 30002, double timeout_s = 2.0);

  /// speedj(qd, a, t): joint velocities (rad/s) reached with acceleration a (rad/s^2), held for t
  /// seconds unless replaced. UserError for non-finite values (nothing is sent) or when the robot
  /// is gone (naming host:port).
  void SpeedJ(const std::array<double, 6>& velocity_rad_s, double acceleration_rad_s2,
              double time_s);
  /// stopj(a): decelerate to zero at a (rad/s^2).
  void StopJ(double acceleration_rad_s2);
  /// set_tool_digital_out(output, value).
  void SetToolDigitalOut(int output, bool value);
  /// Sends a raw script line (a newline is appended when missing).
  void SendLine(std::string line);

  /// False once the controller closed the connection (seen on the next command).
  bool connected() const { return socket_.open(); }
  /// "host:port".
  const std::string& where() const { return where_; }
  int64_t lines_sent() const { return lines_sent_; }

 private:
  std::string where_;
  std::mutex mutex_;
  TcpSocket socket_;
  int64_t lines_sent_ = 0;
};

}  // namespace recon::robot
