#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "devices/robot/rtde_protocol.h"
#include "devices/robot/speedj_motion.h"
#include "devices/robot/tcp_socket.h"
#include "devices/robot/urscript_command.h"

namespace recon::robot {

/// A UR5 controller on loopback, for tests, demos and users without a robot. Two TCP servers:
/// - RTDE (as port 30004): the real handshake (protocol 2 only), output recipes with NOT_FOUND for
///   unknown names (recipe id 0 then), data packages at the recipe's frequency from the current
///   state. Outputs: timestamp, actual_q, actual_qd, target_q, actual_TCP_pose, robot_mode,
///   safety_mode, speed_scaling, actual_digital_output_bits (tool outputs at bits 16, 17).
/// - Script (as port 30002): one URScript line per command, speedj/stopj/set_tool_digital_out;
///   any other line is counted as malformed and ignored, as the controller rejects a program
///   that does not compile.
/// The joints integrate speedj at 125 Hz (SpeedjMotion), from `home_q_rad`. Any number of
/// clients, one after another or at once. Port 0 (the default) picks free ports; ask
/// rtde_port() and script_port(). Every accessor is thread-safe.
class FakeUrController {
 public:
  struct Options {
    /// The simulated UR5's home (engine/worlds/ur5_arm.h kHome): above the table, tool down.
    std::array<double, 6> home_q_rad = {3.14159265358979, -1.9, 1.9, -1.5708, -1.5708, 0.0};
    int rtde_port = 0;
    int script_port = 0;
    RtdeControllerVersion version{5, 11, 0, 108};
    /// A joint past +-this raises a protective stop (safety_mode 3, everything halts).
    double joint_limit_rad = 2 * 3.14159265358979;
    double physics_rate_hz = 125;
  };

  /// Starts listening and moving. UserError when a port cannot be bound.
  explicit FakeUrController(Options options);
  FakeUrController() : FakeUrController(Options{}) {}
  ~FakeUrController();
  FakeUrController(const FakeUrController&) = delete;
  FakeUrController& operator=(const FakeUrController&) = delete;

  int rtde_port() const { return rtde_port_; }
  int script_port() const { return script_port_; }

  std::array<double, 6> q_rad() const;
  std::array<double, 6> qd_rad_s() const;
  int32_t robot_mode() const;
  int32_t safety_mode() const;
  /// Valid script lines received (speedj, stopj, set_tool_digital_out).
  int64_t commands_received() const { return commands_; }
  /// Script lines rejected by the parser.
  int64_t malformed_lines() const { return malformed_; }
  std::optional<UrScriptCommand> last_speedj() const;
  /// Tool digital output 0 or 1; output 0 drives the gripper (true: closed).
  bool tool_output(int index) const;
  /// RTDE data packages sent, over all clients.
  int64_t data_packets_sent() const { return data_packets_; }
  /// RTDE and script connections accepted so far.
  int64_t rtde_clients() const { return rtde_clients_; }
  int64_t script_clients() const { return script_clients_; }

  /// Handles one script line as if it came from the script port (what the servers call).
  void HandleScriptLine(const std::string& line);
  /// Moves the joints to `q_rad`, at rest, with no command in force.
  void Teleport(const std::array<double, 6>& q_rad);
  /// Clears a protective stop (the operator's "unlock" on the pendant).
  void ClearProtectiveStop();
  /// Closes every open connection, as a robot that is switched off or unplugged; new clients are
  /// still accepted until Stop().
  void DisconnectClients();
  /// Closes the servers and all connections; nothing answers afterwards. The destructor calls it.
  void Stop();

 private:
  struct Connection {
    TcpSocket socket;
    std::thread thread;
    std::atomic<bool> done{false};
  };
  void AcceptLoop(TcpListener& listener, bool rtde);
  void ServeRtde(Connection& connection);
  void ServeScript(Connection& connection);
  void PhysicsLoop();
  std::string DataPackage(const RtdeRecipe& recipe);

  Options options_;
  TcpListener rtde_listener_;
  TcpListener script_listener_;
  int rtde_port_;
  int script_port_;

  mutable std::mutex state_mutex_;  // guards the motion, time and outputs below
  SpeedjMotion motion_;
  double time_s_ = 0;  // controller time: physics steps * dt
  std::optional<UrScriptCommand> last_speedj_;
  std::array<bool, 2> tool_outputs_{};

  std::mutex connections_mutex_;
  std::list<std::unique_ptr<Connection>> connections_;
  std::atomic<bool> stop_{false};
  std::atomic<int64_t> commands_{0};
  std::atomic<int64_t> malformed_{0};
  std::atomic<int64_t> data_packets_{0};
  std::atomic<int64_t> rtde_clients_{0};
  std::atomic<int64_t> script_clients_{0};
  std::atomic<int> next_recipe_id_{1};
  std::thread rtde_accept_;
  std::thread script_accept_;
  std::thread physics_;
};

}  // namespace recon::robot
