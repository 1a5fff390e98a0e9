#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "devices/robot/rtde_protocol.h"
#include "devices/robot/tcp_socket.h"

namespace recon::robot {

/// The robot as one RTDE data package tells it. Fields the recipe did not ask for keep their
/// defaults.
struct RtdeState {
  double controller_time_s = 0;  ///< RTDE `timestamp`: seconds since the controller booted
  std::array<double, 6> actual_q_rad{};
  std::array<double, 6> actual_qd_rad_s{};
  std::array<double, 6> target_q_rad{};
  std::array<double, 6> actual_tcp_pose{};  ///< x, y, z (m), rotation vector (rad), base frame
  int32_t robot_mode = -1;                  ///< see RobotModeName (7: RUNNING)
  int32_t safety_mode = 0;                  ///< see SafetyModeName (1: NORMAL)
  double speed_scaling = 0;
  /// RTDE `actual_digital_output_bits`: bits 0-7 standard, 8-15 configurable, 16-17 the tool's.
  uint64_t digital_output_bits = 0;
  /// When the package arrived: the host's steady clock (std::chrono::steady_clock since its
  /// epoch), in seconds, so every device of this process shares the time base.
  double received_s = 0;
  int64_t sequence = 0;  ///< 1 for the first package of this connection, then 2, 3, ...
};

/// A UR controller's RTDE interface (port 30004): negotiates protocol 2, reads the controller
/// version, subscribes to `outputs` at `frequency_hz`, starts the stream, and keeps the latest
/// state on a receive thread. Reading never blocks on the network; a lost connection shows as
/// connected() false with the reason in last_error().
class RtdeClient {
 public:
  struct Options {
    std::string host;
    int port = 30004;
    double frequency_hz = 125;  ///< CB3 streams at most 125 Hz, e-Series 500 Hz
    double timeout_s = 2.0;     ///< to connect, and for each handshake reply
    std::vector<std::string> outputs = DefaultOutputs();
  };
  /// timestamp, actual_q, actual_qd, robot_mode, safety_mode, actual_TCP_pose.
  static std::vector<std::string> DefaultOutputs();

  /// Connects and runs the handshake. UserError naming host:port when nothing answers, the
  /// connection is refused, a reply does not come or is wrong, or an output is NOT_FOUND (naming
  /// it).
  explicit RtdeClient(Options options);
  /// Pauses the stream (best effort) and disconnects.
  ~RtdeClient();
  RtdeClient(const RtdeClient&) = delete;
  RtdeClient& operator=(const RtdeClient&) = delete;

  /// The latest state; nullopt until the first data package.
  std::optional<RtdeState> Latest() const;
  /// Waits up to `timeout_s` for a data package newer than `after_sequence`; false on timeout or
  /// disconnect.
  bool WaitForData(double timeout_s, int64_t after_sequence = 0) const;
  /// False once the controller closed the connection, the stream broke or Disconnect() ran.
  bool connected() const { return connected_; }
  /// Why the connection ended (empty while it is fine).
  std::string last_error() const;
  /// Data packages received on this connection.
  int64_t packets_received() const { return packets_; }
  /// Packages per second over the last second (0 until two have arrived).
  double measured_rate_hz() const;
  /// Protocol errors so far (a corrupt stream, packages that do not fit the recipe).
  int64_t protocol_errors() const { return protocol_errors_; }
  /// The latest text message ('M') from the controller, e.g. a warning.
  std::string last_text_message() const;

  const RtdeControllerVersion& controller_version() const { return controller_version_; }
  const RtdeRecipe& recipe() const { return recipe_; }
  /// "host:port", for messages.
  const std::string& where() const { return where_; }
  double frequency_hz() const { return options_.frequency_hz; }

  /// Stops the receive thread and closes the connection.
  void Disconnect();

 private:
  void Handshake();
  RtdePacket Await(RtdePacketType type, const char* request);
  void ReceiveLoop();
  void Handle(const RtdePacket& packet);
  void Fail(const std::string& why);

  Options options_;
  std::string where_;
  TcpSocket socket_;
  RtdeStreamReader reader_;
  std::deque<RtdePacket> pending_;  // read during the handshake, not yet handled
  RtdeControllerVersion controller_version_;
  RtdeRecipe recipe_;

  mutable std::mutex mutex_;
  mutable std::condition_variable data_arrived_;
  std::optional<RtdeState> latest_;
  std::deque<double> arrivals_s_;  // the last second of arrival times, for the rate
  std::string last_error_;
  std::string last_text_message_;
  std::atomic<bool> connected_{false};
  std::atomic<bool> stop_{false};
  std::atomic<int64_t> packets_{0};
  std::atomic<int64_t> protocol_errors_{0};
  std::thread thread_;
};

}  // namespace recon::robot
