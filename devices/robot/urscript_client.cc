#include "devices/robot/urscript_client.h"

#include "devices/robot/urscript_command.h"
#include "engine/core/error.h"

namespace recon::robot {

UrScriptClient::UrScriptClient(const std::string& host, int port, double timeout_s)
    : where_(host + ":" + std::to_string(port)),
      socket_(TcpSocket::Connect(host, port, timeout_s)) {}

void UrScriptClient::SpeedJ(const std::array<double, 6>& velocity_rad_s, double acceleration_rad_s2,
                            double time_s) {
  SendLine(FormatSpeedJ(velocity_rad_s, acceleration_rad_s2, time_s));
}

void UrScriptClient::StopJ(double acceleration_rad_s2) {
  SendLine(FormatStopJ(acceleration_rad_s2));
}

void UrScriptClient::SetToolDigitalOut(int output, bool value) {
  SendLine(FormatSetToolDigitalOut(output, value));
}

void UrScriptClient::SendLine(std::string line) {
  if (line.empty() || line.back() != '\n') line += '\n';
  std::lock_guard lock(mutex_);
  if (!socket_.open()) {
    throw UserError("the UR script port " + where_ + " is closed (the robot went away)");
  }
  // Drain what the controller streamed since the last command (state packets, about 10 kB/s; at
  // most 64 reads of 4 kB here); a closed socket shows here before the write.
  std::string ignored;
  bool alive = true;
  for (int i = 0; i < 64 && alive; ++i) {
    ignored.clear();
    alive = socket_.Receive(ignored, 0);
    if (ignored.empty()) break;
  }
  if (!alive || !socket_.SendAll(line)) {
    const std::string why = socket_.last_error();
    socket_.Close();
    throw UserError("lost the UR script port " + where_ + ": " + why);
  }
  ++lines_sent_;
}

}  // namespace recon::robot
