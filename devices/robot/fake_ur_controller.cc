#include "devices/robot/fake_ur_controller.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "devices/robot/ur5_kinematics.h"
#include "devices/robot/ur_modes.h"

namespace recon::robot {

namespace {

/// What the fake can stream, with the type a CB3/e-Series controller gives each name.
std::optional<RtdeFieldType> OutputType(const std::string& name) {
  if (name == "timestamp" || name == "speed_scaling") return RtdeFieldType::kDouble;
  if (name == "actual_q" || name == "actual_qd" || name == "target_q" ||
      name == "actual_TCP_pose") {
    return RtdeFieldType::kVector6d;
  }
  if (name == "robot_mode" || name == "safety_mode") return RtdeFieldType::kInt32;
  if (name == "actual_digital_output_bits") return RtdeFieldType::kUint64;
  return std::nullopt;
}

}  // namespace

FakeUrController::FakeUrController(Options options)
    : options_(options),
      rtde_listener_(options.rtde_port),
      script_listener_(options.script_port),
      rtde_port_(rtde_listener_.port()),
      script_port_(script_listener_.port()),
      motion_(options.home_q_rad, options.joint_limit_rad) {
  rtde_accept_ = std::thread([this] { AcceptLoop(rtde_listener_, true); });
  script_accept_ = std::thread([this] { AcceptLoop(script_listener_, false); });
  physics_ = std::thread([this] { PhysicsLoop(); });
}

FakeUrController::~FakeUrController() { Stop(); }

void FakeUrController::Stop() {
  if (stop_.exchange(true)) return;
  if (rtde_accept_.joinable()) rtde_accept_.join();
  if (script_accept_.joinable()) script_accept_.join();
  if (physics_.joinable()) physics_.join();
  rtde_listener_.Close();
  script_listener_.Close();
  DisconnectClients();
  std::lock_guard lock(connections_mutex_);
  for (auto& c : connections_) {
    if (c->thread.joinable()) c->thread.join();
  }
  connections_.clear();
}

void FakeUrController::DisconnectClients() {
  std::lock_guard lock(connections_mutex_);
  for (auto& c : connections_) c->socket.Shutdown();
}

void FakeUrController::AcceptLoop(TcpListener& listener, bool rtde) {
  while (!stop_) {
    TcpSocket socket = listener.Accept(50);
    std::lock_guard lock(connections_mutex_);
    // Reap finished sessions so a long demo does not collect threads.
    for (auto it = connections_.begin(); it != connections_.end();) {
      if ((*it)->done) {
        (*it)->thread.join();
        it = connections_.erase(it);
      } else {
        ++it;
      }
    }
    if (!socket.open()) continue;
    auto connection = std::make_unique<Connection>();
    connection->socket = std::move(socket);
    Connection* c = connection.get();
    if (rtde) {
      ++rtde_clients_;
      c->thread = std::thread([this, c] {
        ServeRtde(*c);
        c->done = true;
      });
    } else {
      ++script_clients_;
      c->thread = std::thread([this, c] {
        ServeScript(*c);
        c->done = true;
      });
    }
    connections_.push_back(std::move(connection));
  }
}

void FakeUrController::ServeRtde(Connection& connection) {
  TcpSocket& socket = connection.socket;
  RtdeStreamReader reader;
  std::vector<RtdePacket> packets;
  std::optional<RtdeRecipe> recipe;
  bool negotiated = false;
  bool started = false;
  uint8_t next_recipe_id = 1;
  auto period = std::chrono::nanoseconds(0);
  auto next_send = std::chrono::steady_clock::now();
  std::string bytes;
  while (!stop_) {
    int wait_ms = 50;
    if (started) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          next_send - std::chrono::steady_clock::now());
      wait_ms = static_cast<int>(std::clamp<int64_t>(left.count(), 0, 50));
    }
    bytes.clear();
    if (!socket.Receive(bytes, wait_ms)) return;
    packets.clear();
    if (!reader.Feed(bytes, packets)) return;  // a controller drops a client that lost sync
    for (const RtdePacket& p : packets) {
      std::string reply;
      switch (static_cast<RtdePacketType>(p.type)) {
        case RtdePacketType::kRequestProtocolVersion: {
          const auto version = DecodeRequestProtocolVersion(p.payload);
          negotiated = version && *version == kRtdeProtocolVersion;
          reply = EncodeAccepted(RtdePacketType::kRequestProtocolVersion, negotiated);
          break;
        }
        case RtdePacketType::kGetControllerVersion:
          reply = EncodeControllerVersion(options_.version);
          break;
        case RtdePacketType::kSetupOutputs: {
          const auto request = DecodeSetupOutputs(p.payload);
          RtdeRecipe r;
          std::vector<std::string> types;
          bool ok = request && negotiated && !started && request->frequency_hz > 0 &&
                    request->frequency_hz <= 500 && !request->names.empty();
          if (request) {
            for (const std::string& name : request->names) {
              const auto type = OutputType(name);
              types.push_back(type ? RtdeFieldTypeName(*type) : "NOT_FOUND");
              ok = ok && type.has_value();
              if (type) r.types.push_back(*type);
              r.names.push_back(name);
            }
          }
          r.id = ok ? next_recipe_id++ : 0;
          if (ok) {
            recipe = r;
            period = std::chrono::nanoseconds(static_cast<int64_t>(1e9 / request->frequency_hz));
          }
          reply = EncodeSetupOutputsReply(r.id, types);
          break;
        }
        case RtdePacketType::kSetupInputs: {
          // No inputs are writable on the fake: every name is NOT_FOUND, recipe id 0.
          const size_t names =
              p.payload.empty() ? 0 : 1 + std::count(p.payload.begin(), p.payload.end(), ',');
          const std::vector<std::string> types(names, "NOT_FOUND");
          std::string payload(1, '\0');
          for (size_t i = 0; i < types.size(); ++i) {
            if (i > 0) payload += ',';
            payload += types[i];
          }
          reply = EncodeRtdePacket(RtdePacketType::kSetupInputs, payload);
          break;
        }
        case RtdePacketType::kStart:
          started = recipe.has_value();
          next_send = std::chrono::steady_clock::now();
          reply = EncodeAccepted(RtdePacketType::kStart, started);
          break;
        case RtdePacketType::kPause:
          started = false;
          reply = EncodeAccepted(RtdePacketType::kPause, true);
          break;
        default:
          reply = EncodeTextMessage({"unknown RTDE command " + std::to_string(p.type), "RTDE", 1});
      }
      if (!socket.SendAll(reply)) return;
    }
    if (started && std::chrono::steady_clock::now() >= next_send) {
      // Counted as it is handed to the socket, before the client can have it: a client never
      // counts more packages than this.
      ++data_packets_;
      if (!socket.SendAll(DataPackage(*recipe))) return;
      next_send += period;
      // Behind by more than a few periods (a loaded machine): skip ahead instead of bursting.
      if (std::chrono::steady_clock::now() > next_send + 4 * period) {
        next_send = std::chrono::steady_clock::now() + period;
      }
    }
  }
}

std::string FakeUrController::DataPackage(const RtdeRecipe& recipe) {
  std::array<double, 6> q, qd;
  double time_s;
  int32_t robot_mode, safety_mode;
  uint64_t output_bits = 0;
  {
    std::lock_guard lock(state_mutex_);
    q = motion_.q_rad();
    qd = motion_.qd_rad_s();
    time_s = time_s_;
    robot_mode = kRobotModeRunning;
    safety_mode = motion_.protective_stop() ? kSafetyModeProtectiveStop : kSafetyModeNormal;
    for (size_t i = 0; i < tool_outputs_.size(); ++i) {
      if (tool_outputs_[i]) output_bits |= uint64_t{1} << (16 + i);
    }
  }
  std::vector<RtdeValue> values;
  for (const std::string& name : recipe.names) {
    if (name == "timestamp") values.emplace_back(time_s);
    if (name == "speed_scaling") values.emplace_back(1.0);
    if (name == "actual_q" || name == "target_q") values.emplace_back(q);
    if (name == "actual_qd") values.emplace_back(qd);
    if (name == "actual_TCP_pose") values.emplace_back(Ur5TcpPose(q));
    if (name == "robot_mode") values.emplace_back(robot_mode);
    if (name == "safety_mode") values.emplace_back(safety_mode);
    if (name == "actual_digital_output_bits") values.emplace_back(output_bits);
  }
  return PackDataPackage(recipe, values);
}

void FakeUrController::ServeScript(Connection& connection) {
  std::string buffer;
  while (!stop_) {
    if (!connection.socket.Receive(buffer, 50)) return;
    size_t newline;
    while ((newline = buffer.find('\n')) != std::string::npos) {
      std::string line = buffer.substr(0, newline);
      buffer.erase(0, newline + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      HandleScriptLine(line);
    }
    // A line longer than any program RECON sends: reject it rather than buffer without end.
    if (buffer.size() > 65536) {
      ++malformed_;
      buffer.clear();
    }
  }
}

void FakeUrController::HandleScriptLine(const std::string& line) {
  if (line.find_first_not_of(" \t\r") == std::string::npos) return;  // blank: nothing to run
  const std::optional<UrScriptCommand> command = ParseUrScriptLine(line);
  if (!command) {
    ++malformed_;
    return;
  }
  ++commands_;
  std::lock_guard lock(state_mutex_);
  if (command->kind == UrScriptCommand::Kind::kSetToolDigitalOut) {
    tool_outputs_[static_cast<size_t>(command->tool_output)] = command->tool_value;
    return;
  }
  if (command->kind == UrScriptCommand::Kind::kSpeedJ) last_speedj_ = command;
  motion_.Apply(*command, time_s_);
}

void FakeUrController::PhysicsLoop() {
  const double dt_s = 1.0 / options_.physics_rate_hz;
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(dt_s));
  auto next = std::chrono::steady_clock::now();
  while (!stop_) {
    next += period;
    std::this_thread::sleep_until(next);
    // Controller time follows the steps, not the wall clock: a descheduled process loses time
    // like a real controller's cycle overrun would, but never jumps.
    std::lock_guard lock(state_mutex_);
    time_s_ += dt_s;
    motion_.Step(dt_s, time_s_);
  }
}

std::array<double, 6> FakeUrController::q_rad() const {
  std::lock_guard lock(state_mutex_);
  return motion_.q_rad();
}

std::array<double, 6> FakeUrController::qd_rad_s() const {
  std::lock_guard lock(state_mutex_);
  return motion_.qd_rad_s();
}

int32_t FakeUrController::robot_mode() const { return kRobotModeRunning; }

int32_t FakeUrController::safety_mode() const {
  std::lock_guard lock(state_mutex_);
  return motion_.protective_stop() ? kSafetyModeProtectiveStop : kSafetyModeNormal;
}

std::optional<UrScriptCommand> FakeUrController::last_speedj() const {
  std::lock_guard lock(state_mutex_);
  return last_speedj_;
}

bool FakeUrController::tool_output(int index) const {
  std::lock_guard lock(state_mutex_);
  return index >= 0 && index < 2 && tool_outputs_[static_cast<size_t>(index)];
}

void FakeUrController::Teleport(const std::array<double, 6>& q_rad) {
  std::lock_guard lock(state_mutex_);
  motion_.Teleport(q_rad);
}

void FakeUrController::ClearProtectiveStop() {
  std::lock_guard lock(state_mutex_);
  motion_.ClearProtectiveStop();
}

}  // namespace recon::robot
