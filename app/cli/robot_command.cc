#include "app/cli/robot_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <thread>

#include "app/cli/option_checks.h"
#include "devices/robot/fake_ur_controller.h"
#include "devices/robot/rtde_client.h"
#include "devices/robot/tcp_socket.h"
#include "devices/robot/ur_modes.h"
#include "engine/core/error.h"

namespace recon::cli {

namespace {

struct StatusFlags {
  std::string host;
  int rtde_port = 30004;
  int script_port = 30002;
  double seconds = 1.0;  ///< how long to measure the data rate
  bool json = false;
  bool fake = false;
};

constexpr const char* kJointNames[6] = {"base",    "shoulder", "elbow",
                                        "wrist 1", "wrist 2",  "wrist 3"};

/// Whether the script port accepts a connection (nothing is sent: a line there would run).
std::string ProbeScriptPort(const std::string& host, int port) {
  try {
    robot::TcpSocket::Connect(host, port, 1.0);
    return "";
  } catch (const UserError& e) {
    return e.what();
  }
}

void RunStatus(StatusFlags flags) {
  std::unique_ptr<robot::FakeUrController> fake;
  if (flags.fake) {
    fake = std::make_unique<robot::FakeUrController>();
    flags.host = "127.0.0.1";
    flags.rtde_port = fake->rtde_port();
    flags.script_port = fake->script_port();
    std::fprintf(stderr,
                 "recon robot status: a fake UR5 controller on 127.0.0.1 (RTDE :%d, "
                 "script :%d)\n",
                 flags.rtde_port, flags.script_port);
  } else if (flags.host.empty()) {
    throw UserError("robot status needs --host (the robot's IP address) or --fake");
  }
  robot::RtdeClient::Options options;
  options.host = flags.host;
  options.port = flags.rtde_port;
  robot::RtdeClient rtde(options);  // UserError naming host:port when nothing answers
  if (!rtde.WaitForData(2.0)) {
    throw UserError("no RTDE data from " + rtde.where() + " within 2 s" +
                    (rtde.last_error().empty() ? "" : ": " + rtde.last_error()));
  }
  const int64_t first = rtde.packets_received();
  const auto start = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(flags.seconds));
  const double measured_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int64_t packets = rtde.packets_received() - first;
  const double rate_hz = measured_s > 0 ? static_cast<double>(packets) / measured_s : 0;
  if (!rtde.connected()) throw UserError(rtde.last_error());
  const robot::RtdeState s = *rtde.Latest();
  const std::string script_error = ProbeScriptPort(flags.host, flags.script_port);

  constexpr double kDeg = 180.0 / std::numbers::pi;
  if (flags.json) {
    nlohmann::json q_deg = nlohmann::json::array(), qd = nlohmann::json::array();
    for (size_t i = 0; i < 6; ++i) {
      q_deg.push_back(s.actual_q_rad[i] * kDeg);
      qd.push_back(s.actual_qd_rad_s[i]);
    }
    nlohmann::json out = {{"host", flags.host},
                          {"rtde_port", flags.rtde_port},
                          {"script_port", flags.script_port},
                          {"script_port_open", script_error.empty()},
                          {"fake", flags.fake},
                          {"controller_version", rtde.controller_version().ToString()},
                          {"robot_mode", s.robot_mode},
                          {"robot_mode_name", robot::RobotModeName(s.robot_mode)},
                          {"safety_mode", s.safety_mode},
                          {"safety_mode_name", robot::SafetyModeName(s.safety_mode)},
                          {"q_deg", q_deg},
                          {"qd_rad_s", qd},
                          {"tcp_pose", s.actual_tcp_pose},
                          {"packets", packets},
                          {"seconds", measured_s},
                          {"rate_hz", rate_hz},
                          {"requested_rate_hz", rtde.frequency_hz()}};
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("UR controller %s at %s%s\n", rtde.controller_version().ToString().c_str(),
              flags.host.c_str(), flags.fake ? " (fake)" : "");
  std::printf("robot mode   %s (%d)\n", robot::RobotModeName(s.robot_mode).c_str(), s.robot_mode);
  std::printf("safety mode  %s (%d)\n", robot::SafetyModeName(s.safety_mode).c_str(),
              s.safety_mode);
  std::printf("joint        position (deg)  velocity (rad/s)\n");
  for (size_t i = 0; i < 6; ++i) {
    std::printf("  %-9s  %12.2f  %14.3f\n", kJointNames[i], s.actual_q_rad[i] * kDeg,
                s.actual_qd_rad_s[i]);
  }
  const auto& p = s.actual_tcp_pose;
  std::printf("tool         x %.3f  y %.3f  z %.3f m  rotation [%.3f %.3f %.3f] rad\n", p[0], p[1],
              p[2], p[3], p[4], p[5]);
  std::printf("RTDE :%d     %lld packages in %.2f s: %.1f Hz (asked for %g Hz)\n", flags.rtde_port,
              static_cast<long long>(packets), measured_s, rate_hz, rtde.frequency_hz());
  if (script_error.empty()) {
    std::printf("script :%d   accepts connections\n", flags.script_port);
  } else {
    std::printf("script :%d   %s (enable remote control on the pendant to send motion)\n",
                flags.script_port, script_error.c_str());
  }
}

}  // namespace

void AddRobotCommand(CLI::App& app) {
  CLI::App* robot = app.add_subcommand("robot", "a Universal Robots arm over RTDE and URScript");
  robot->require_subcommand(1);
  auto flags = std::make_shared<StatusFlags>();
  CLI::App* status = robot->add_subcommand(
      "status", "connect to a UR controller and report its modes, joints and data rate");
  status->add_option("--host", flags->host, "the robot's IP address or name");
  status->add_option("--rtde-port", flags->rtde_port, "RTDE port")
      ->capture_default_str()
      ->check(WholeBetween(1, 65535));
  status->add_option("--script-port", flags->script_port, "URScript (primary interface) port")
      ->capture_default_str()
      ->check(WholeBetween(1, 65535));
  status->add_option("--seconds", flags->seconds, "how long to measure the data rate")
      ->capture_default_str()
      ->check(NumberBetween(0, 3600));
  status->add_flag("--json", flags->json, "one JSON object instead of the table");
  status->add_flag("--fake", flags->fake,
                   "report against a built-in fake UR5 controller on loopback (no robot needed)");
  status->callback([flags] { RunStatus(*flags); });
}

}  // namespace recon::cli
