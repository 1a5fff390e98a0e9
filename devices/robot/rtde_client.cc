#include "devices/robot/rtde_client.h"

#include <chrono>
#include <cstdio>

#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::robot {

namespace {

std::string Seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", s);
  return text;
}

/// The field type each output we understand must have; outputs not listed are accepted and
/// ignored.
std::optional<RtdeFieldType> ExpectedType(const std::string& name) {
  if (name == "timestamp" || name == "speed_scaling") return RtdeFieldType::kDouble;
  if (name == "actual_q" || name == "actual_qd" || name == "target_q" ||
      name == "actual_TCP_pose") {
    return RtdeFieldType::kVector6d;
  }
  if (name == "robot_mode" || name == "safety_mode") return RtdeFieldType::kInt32;
  return std::nullopt;
}

}  // namespace

std::vector<std::string> RtdeClient::DefaultOutputs() {
  return {"timestamp", "actual_q", "actual_qd", "robot_mode", "safety_mode", "actual_TCP_pose"};
}

RtdeClient::RtdeClient(Options options)
    : options_(std::move(options)), where_(options_.host + ":" + std::to_string(options_.port)) {
  if (!(options_.frequency_hz > 0 && options_.frequency_hz <= 500)) {
    throw UserError("RTDE frequency " + Seconds(options_.frequency_hz) + " Hz for " + where_ +
                    " is out of range (0..500 Hz)");
  }
  if (options_.outputs.empty()) throw UserError("no RTDE outputs to ask " + where_ + " for");
  socket_ = TcpSocket::Connect(options_.host, options_.port, options_.timeout_s);
  Handshake();
  connected_ = true;
  thread_ = std::thread([this] { ReceiveLoop(); });
}

RtdeClient::~RtdeClient() {
  if (connected_) socket_.SendAll(EncodeRtdePacket(RtdePacketType::kPause));
  Disconnect();
}

RtdePacket RtdeClient::Await(RtdePacketType type, const char* request) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options_.timeout_s));
  std::vector<RtdePacket> packets;
  for (;;) {
    while (!pending_.empty()) {
      RtdePacket packet = std::move(pending_.front());
      pending_.pop_front();
      if (packet.type == static_cast<uint8_t>(type)) return packet;
      if (packet.type == static_cast<uint8_t>(RtdePacketType::kTextMessage)) {
        if (auto m = DecodeTextMessage(packet.payload)) last_text_message_ = m->message;
        continue;
      }
      throw UserError("unexpected RTDE reply from " + where_ + " to " + request + ": packet type " +
                      std::to_string(packet.type) + " (is " + std::to_string(options_.port) +
                      " the RTDE port, 30004?)");
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      throw UserError("no RTDE reply from " + where_ + " to " + request + " within " +
                      Seconds(options_.timeout_s) + " s (is " + std::to_string(options_.port) +
                      " the RTDE port, 30004?)");
    }
    std::string bytes;
    if (!socket_.Receive(bytes, static_cast<int>(left.count()))) {
      throw UserError("the UR controller at " + where_ + " hung up during the RTDE handshake (" +
                      request + "): " + socket_.last_error());
    }
    packets.clear();
    if (!reader_.Feed(bytes, packets)) {
      throw UserError("not an RTDE stream from " + where_ + " (is " +
                      std::to_string(options_.port) +
                      " the RTDE port, 30004?): " + reader_.error());
    }
    for (RtdePacket& p : packets) pending_.push_back(std::move(p));
  }
}

void RtdeClient::Handshake() {
  socket_.SendAll(EncodeRequestProtocolVersion(kRtdeProtocolVersion));
  const std::optional<bool> accepted = DecodeAccepted(
      Await(RtdePacketType::kRequestProtocolVersion, "the protocol version").payload);
  if (!accepted) throw UserError("malformed protocol version reply from " + where_);
  if (!*accepted) {
    throw UserError("the UR controller at " + where_ +
                    " refused RTDE protocol version 2 (it needs software 3.5 / 5.0 or newer)");
  }

  socket_.SendAll(EncodeRtdePacket(RtdePacketType::kGetControllerVersion));
  const auto version = DecodeControllerVersion(
      Await(RtdePacketType::kGetControllerVersion, "the controller version").payload);
  if (!version) throw UserError("malformed controller version reply from " + where_);
  controller_version_ = *version;

  socket_.SendAll(EncodeSetupOutputs(options_.frequency_hz, options_.outputs));
  const auto reply =
      DecodeSetupOutputsReply(Await(RtdePacketType::kSetupOutputs, "the output setup").payload);
  if (!reply) throw UserError("malformed output setup reply from " + where_);
  if (reply->types.size() != options_.outputs.size()) {
    throw UserError("the UR controller at " + where_ + " answered " +
                    std::to_string(reply->types.size()) + " output types for " +
                    std::to_string(options_.outputs.size()) + " outputs");
  }
  recipe_ = RtdeRecipe{reply->recipe_id, options_.outputs, {}};
  for (size_t i = 0; i < reply->types.size(); ++i) {
    const std::string& name = options_.outputs[i];
    const std::optional<RtdeFieldType> type = ParseRtdeFieldType(reply->types[i]);
    if (!type) {
      throw UserError("the UR controller at " + where_ + " has no RTDE output '" + name + "' (" +
                      reply->types[i] + "; controller " + controller_version_.ToString() + ")");
    }
    const std::optional<RtdeFieldType> expected = ExpectedType(name);
    if (expected && *expected != *type) {
      throw UserError("RTDE output '" + name + "' of " + where_ + " is " + reply->types[i] +
                      ", expected " + RtdeFieldTypeName(*expected));
    }
    recipe_.types.push_back(*type);
  }
  if (recipe_.id == 0) {
    throw UserError("the UR controller at " + where_ + " refused the RTDE outputs at " +
                    Seconds(options_.frequency_hz) + " Hz (recipe id 0)");
  }

  socket_.SendAll(EncodeRtdePacket(RtdePacketType::kStart));
  const auto started = DecodeAccepted(Await(RtdePacketType::kStart, "start").payload);
  if (!started || !*started) {
    throw UserError("the UR controller at " + where_ + " refused to start the RTDE stream");
  }
}

void RtdeClient::ReceiveLoop() {
  std::vector<RtdePacket> packets;
  for (RtdePacket& p : pending_) Handle(p);
  pending_.clear();
  std::string bytes;
  while (!stop_) {
    bytes.clear();
    if (!socket_.Receive(bytes, 100)) {
      if (!stop_)
        Fail("the UR controller at " + where_ + " closed the RTDE connection (" +
             socket_.last_error() + ")");
      return;
    }
    packets.clear();
    if (!reader_.Feed(bytes, packets)) {
      ++protocol_errors_;
      Fail("broken RTDE stream from " + where_ + ": " + reader_.error());
      return;
    }
    for (const RtdePacket& p : packets) Handle(p);
  }
}

void RtdeClient::Handle(const RtdePacket& packet) {
  if (packet.type == static_cast<uint8_t>(RtdePacketType::kTextMessage)) {
    if (auto m = DecodeTextMessage(packet.payload)) {
      std::lock_guard lock(mutex_);
      last_text_message_ = m->source + ": " + m->message;
    }
    return;
  }
  if (packet.type != static_cast<uint8_t>(RtdePacketType::kDataPackage)) return;
  std::string why;
  const auto values = UnpackDataPackage(recipe_, packet.payload, &why);
  if (!values) {
    ++protocol_errors_;
    return;
  }
  const double now_s = SteadySeconds();
  RtdeState state;
  for (size_t i = 0; i < values->size(); ++i) {
    const std::string& name = recipe_.names[i];
    const RtdeValue& v = (*values)[i];
    if (name == "timestamp") state.controller_time_s = std::get<double>(v);
    if (name == "speed_scaling") state.speed_scaling = std::get<double>(v);
    if (name == "actual_q") state.actual_q_rad = std::get<std::array<double, 6>>(v);
    if (name == "actual_qd") state.actual_qd_rad_s = std::get<std::array<double, 6>>(v);
    if (name == "target_q") state.target_q_rad = std::get<std::array<double, 6>>(v);
    if (name == "actual_TCP_pose") state.actual_tcp_pose = std::get<std::array<double, 6>>(v);
    if (name == "robot_mode") state.robot_mode = std::get<int32_t>(v);
    if (name == "safety_mode") state.safety_mode = std::get<int32_t>(v);
    if (name == "actual_digital_output_bits") state.digital_output_bits = std::get<uint64_t>(v);
  }
  state.received_s = now_s;
  state.sequence = ++packets_;
  {
    std::lock_guard lock(mutex_);
    latest_ = state;
    arrivals_s_.push_back(now_s);
    while (arrivals_s_.front() < now_s - 1.0) arrivals_s_.pop_front();
  }
  data_arrived_.notify_all();
}

void RtdeClient::Fail(const std::string& why) {
  {
    std::lock_guard lock(mutex_);
    if (last_error_.empty()) last_error_ = why;
  }
  connected_ = false;
  data_arrived_.notify_all();
}

std::optional<RtdeState> RtdeClient::Latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

bool RtdeClient::WaitForData(double timeout_s, int64_t after_sequence) const {
  std::unique_lock lock(mutex_);
  return data_arrived_.wait_for(
             lock, std::chrono::duration<double>(timeout_s),
             [&] { return (latest_ && latest_->sequence > after_sequence) || !connected_; }) &&
         latest_ && latest_->sequence > after_sequence;
}

std::string RtdeClient::last_error() const {
  std::lock_guard lock(mutex_);
  return last_error_;
}

std::string RtdeClient::last_text_message() const {
  std::lock_guard lock(mutex_);
  return last_text_message_;
}

double RtdeClient::measured_rate_hz() const {
  std::lock_guard lock(mutex_);
  if (arrivals_s_.size() < 2) return 0;
  const double span_s = arrivals_s_.back() - arrivals_s_.front();
  return span_s > 0 ? static_cast<double>(arrivals_s_.size() - 1) / span_s : 0;
}

void RtdeClient::Disconnect() {
  stop_ = true;
  socket_.Shutdown();
  if (thread_.joinable()) thread_.join();
  socket_.Close();
  if (connected_) Fail("disconnected from " + where_);
}

}  // namespace recon::robot
