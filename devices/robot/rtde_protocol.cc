#include "devices/robot/rtde_protocol.h"

#include <bit>
#include <cstring>
#include <stdexcept>

namespace recon::robot {

namespace {

void PutU8(std::string& out, uint8_t v) { out.push_back(static_cast<char>(v)); }

template <typename T>
void PutBigEndian(std::string& out, T v) {
  for (int shift = 8 * (static_cast<int>(sizeof(T)) - 1); shift >= 0; shift -= 8) {
    out.push_back(static_cast<char>((static_cast<uint64_t>(v) >> shift) & 0xFF));
  }
}

void PutDouble(std::string& out, double v) { PutBigEndian(out, std::bit_cast<uint64_t>(v)); }

/// Reads big-endian numbers from a payload; every read checks the bounds first and a failed read
/// leaves `ok` false for good.
class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  bool ok() const { return ok_; }
  size_t left() const { return bytes_.size() - at_; }
  bool Has(size_t n) {
    if (!ok_ || left() < n) ok_ = false;
    return ok_;
  }
  template <typename T>
  T Big() {
    if (!Has(sizeof(T))) return T{};
    uint64_t v = 0;
    for (size_t i = 0; i < sizeof(T); ++i) v = (v << 8) | static_cast<uint8_t>(bytes_[at_ + i]);
    at_ += sizeof(T);
    return static_cast<T>(v);
  }
  double Double() { return std::bit_cast<double>(Big<uint64_t>()); }
  std::string Bytes(size_t n) {
    if (!Has(n)) return {};
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::string Rest() { return Bytes(left()); }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
  bool ok_ = true;
};

std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> parts;
  if (text.empty()) return parts;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return parts;
}

std::string JoinCommas(const std::vector<std::string>& parts) {
  std::string text;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) text += ',';
    text += parts[i];
  }
  return text;
}

struct FieldTypeName {
  RtdeFieldType type;
  const char* name;
  size_t size;
};
constexpr FieldTypeName kFieldTypes[] = {
    {RtdeFieldType::kDouble, "DOUBLE", 8},      {RtdeFieldType::kVector6d, "VECTOR6D", 48},
    {RtdeFieldType::kVector3d, "VECTOR3D", 24}, {RtdeFieldType::kInt32, "INT32", 4},
    {RtdeFieldType::kUint32, "UINT32", 4},      {RtdeFieldType::kUint64, "UINT64", 8},
    {RtdeFieldType::kUint8, "UINT8", 1},        {RtdeFieldType::kBool, "BOOL", 1},
};

}  // namespace

std::string EncodeRtdePacket(uint8_t type, const std::string& payload) {
  const size_t size = kRtdeHeaderSize + payload.size();
  if (size > kRtdeMaxPacketSize) {
    throw std::length_error("RTDE packet of " + std::to_string(size) + " bytes is too large");
  }
  std::string out;
  out.reserve(size);
  PutBigEndian(out, static_cast<uint16_t>(size));
  PutU8(out, type);
  return out + payload;
}

std::optional<RtdeFieldType> ParseRtdeFieldType(const std::string& name) {
  for (const FieldTypeName& t : kFieldTypes) {
    if (name == t.name) return t.type;
  }
  return std::nullopt;
}

std::string RtdeFieldTypeName(RtdeFieldType type) {
  for (const FieldTypeName& t : kFieldTypes) {
    if (t.type == type) return t.name;
  }
  return "?";
}

size_t RtdeFieldSize(RtdeFieldType type) {
  for (const FieldTypeName& t : kFieldTypes) {
    if (t.type == type) return t.size;
  }
  return 0;
}

size_t RtdeRecipe::PayloadSize() const {
  size_t size = 0;
  for (RtdeFieldType t : types) size += RtdeFieldSize(t);
  return size;
}

std::string EncodeRequestProtocolVersion(uint16_t version) {
  std::string payload;
  PutBigEndian(payload, version);
  return EncodeRtdePacket(RtdePacketType::kRequestProtocolVersion, payload);
}

std::optional<uint16_t> DecodeRequestProtocolVersion(const std::string& payload) {
  Reader r(payload);
  const uint16_t version = r.Big<uint16_t>();
  if (!r.ok() || r.left() != 0) return std::nullopt;
  return version;
}

std::string EncodeAccepted(RtdePacketType type, bool accepted) {
  return EncodeRtdePacket(type, std::string(1, accepted ? 1 : 0));
}

std::optional<bool> DecodeAccepted(const std::string& payload) {
  if (payload.size() != 1) return std::nullopt;
  return payload[0] != 0;
}

std::string RtdeControllerVersion::ToString() const {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(bugfix) + "." +
         std::to_string(build);
}

std::string EncodeControllerVersion(const RtdeControllerVersion& version) {
  std::string payload;
  for (uint32_t v : {version.major, version.minor, version.bugfix, version.build}) {
    PutBigEndian(payload, v);
  }
  return EncodeRtdePacket(RtdePacketType::kGetControllerVersion, payload);
}

std::optional<RtdeControllerVersion> DecodeControllerVersion(const std::string& payload) {
  Reader r(payload);
  RtdeControllerVersion v;
  v.major = r.Big<uint32_t>();
  v.minor = r.Big<uint32_t>();
  v.bugfix = r.Big<uint32_t>();
  v.build = r.Big<uint32_t>();
  if (!r.ok() || r.left() != 0) return std::nullopt;
  return v;
}

std::string EncodeSetupOutputs(double frequency_hz, const std::vector<std::string>& names) {
  std::string payload;
  PutDouble(payload, frequency_hz);
  return EncodeRtdePacket(RtdePacketType::kSetupOutputs, payload + JoinCommas(names));
}

std::optional<RtdeSetupOutputsRequest> DecodeSetupOutputs(const std::string& payload) {
  Reader r(payload);
  RtdeSetupOutputsRequest request;
  request.frequency_hz = r.Double();
  request.names = SplitCommas(r.Rest());
  if (!r.ok()) return std::nullopt;
  return request;
}

std::string EncodeSetupOutputsReply(uint8_t recipe_id, const std::vector<std::string>& types) {
  std::string payload;
  PutU8(payload, recipe_id);
  return EncodeRtdePacket(RtdePacketType::kSetupOutputs, payload + JoinCommas(types));
}

std::optional<RtdeSetupOutputsReply> DecodeSetupOutputsReply(const std::string& payload) {
  Reader r(payload);
  RtdeSetupOutputsReply reply;
  reply.recipe_id = r.Big<uint8_t>();
  reply.types = SplitCommas(r.Rest());
  if (!r.ok()) return std::nullopt;
  return reply;
}

std::string EncodeTextMessage(const RtdeTextMessage& message) {
  std::string payload;
  const std::string text = message.message.substr(0, 255);
  const std::string source = message.source.substr(0, 255);
  PutU8(payload, static_cast<uint8_t>(text.size()));
  payload += text;
  PutU8(payload, static_cast<uint8_t>(source.size()));
  payload += source;
  PutU8(payload, message.level);
  return EncodeRtdePacket(RtdePacketType::kTextMessage, payload);
}

std::optional<RtdeTextMessage> DecodeTextMessage(const std::string& payload) {
  Reader r(payload);
  RtdeTextMessage m;
  m.message = r.Bytes(r.Big<uint8_t>());
  m.source = r.Bytes(r.Big<uint8_t>());
  m.level = r.Big<uint8_t>();
  if (!r.ok() || r.left() != 0) return std::nullopt;
  return m;
}

std::string PackDataPackage(const RtdeRecipe& recipe, const std::vector<RtdeValue>& values) {
  if (values.size() != recipe.types.size()) {
    throw std::invalid_argument("data package with " + std::to_string(values.size()) +
                                " values for a recipe of " + std::to_string(recipe.types.size()));
  }
  std::string payload;
  PutU8(payload, recipe.id);
  for (size_t i = 0; i < values.size(); ++i) {
    const RtdeValue& v = values[i];
    const RtdeFieldType t = recipe.types[i];
    const bool matches =
        (t == RtdeFieldType::kDouble && std::holds_alternative<double>(v)) ||
        (t == RtdeFieldType::kVector6d && std::holds_alternative<std::array<double, 6>>(v)) ||
        (t == RtdeFieldType::kVector3d && std::holds_alternative<std::array<double, 3>>(v)) ||
        (t == RtdeFieldType::kInt32 && std::holds_alternative<int32_t>(v)) ||
        (t == RtdeFieldType::kUint32 && std::holds_alternative<uint32_t>(v)) ||
        (t == RtdeFieldType::kUint64 && std::holds_alternative<uint64_t>(v)) ||
        (t == RtdeFieldType::kUint8 && std::holds_alternative<uint8_t>(v)) ||
        (t == RtdeFieldType::kBool && std::holds_alternative<bool>(v));
    if (!matches) {
      throw std::invalid_argument("value " + std::to_string(i) + " is not a " +
                                  RtdeFieldTypeName(t));
    }
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, double>) {
            PutDouble(payload, x);
          } else if constexpr (std::is_same_v<T, bool>) {
            PutU8(payload, x ? 1 : 0);
          } else if constexpr (std::is_integral_v<T>) {
            PutBigEndian(payload, x);
          } else {
            for (double e : x) PutDouble(payload, e);
          }
        },
        v);
  }
  return EncodeRtdePacket(RtdePacketType::kDataPackage, payload);
}

std::optional<std::vector<RtdeValue>> UnpackDataPackage(const RtdeRecipe& recipe,
                                                        const std::string& payload,
                                                        std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<std::vector<RtdeValue>> {
    if (why != nullptr) *why = reason;
    return std::nullopt;
  };
  Reader r(payload);
  const uint8_t id = r.Big<uint8_t>();
  if (!r.ok()) return fail("empty data package");
  if (id != recipe.id) {
    return fail("data package for recipe " + std::to_string(id) + ", expected " +
                std::to_string(recipe.id));
  }
  if (r.left() != recipe.PayloadSize()) {
    return fail("data package of " + std::to_string(r.left()) + " bytes, the recipe needs " +
                std::to_string(recipe.PayloadSize()));
  }
  std::vector<RtdeValue> values;
  values.reserve(recipe.types.size());
  for (RtdeFieldType t : recipe.types) {
    switch (t) {
      case RtdeFieldType::kDouble:
        values.emplace_back(r.Double());
        break;
      case RtdeFieldType::kVector6d: {
        std::array<double, 6> v{};
        for (double& e : v) e = r.Double();
        values.emplace_back(v);
        break;
      }
      case RtdeFieldType::kVector3d: {
        std::array<double, 3> v{};
        for (double& e : v) e = r.Double();
        values.emplace_back(v);
        break;
      }
      case RtdeFieldType::kInt32:
        values.emplace_back(r.Big<int32_t>());
        break;
      case RtdeFieldType::kUint32:
        values.emplace_back(r.Big<uint32_t>());
        break;
      case RtdeFieldType::kUint64:
        values.emplace_back(r.Big<uint64_t>());
        break;
      case RtdeFieldType::kUint8:
        values.emplace_back(r.Big<uint8_t>());
        break;
      case RtdeFieldType::kBool:
        values.emplace_back(r.Big<uint8_t>() != 0);
        break;
    }
  }
  if (!r.ok()) return fail("truncated data package");  // unreachable after the size check
  return values;
}

RtdeStreamReader::RtdeStreamReader(size_t max_packet_size) : max_packet_size_(max_packet_size) {}

bool RtdeStreamReader::Feed(const char* data, size_t size, std::vector<RtdePacket>& out) {
  stats_.bytes += static_cast<int64_t>(size);
  if (corrupt_) {
    stats_.discarded += static_cast<int64_t>(size);
    return false;
  }
  buffer_.append(data, size);
  size_t at = 0;
  while (buffer_.size() - at >= kRtdeHeaderSize) {
    const size_t packet_size = (static_cast<size_t>(static_cast<uint8_t>(buffer_[at])) << 8) |
                               static_cast<uint8_t>(buffer_[at + 1]);
    if (packet_size < kRtdeHeaderSize || packet_size > max_packet_size_) {
      corrupt_ = true;
      ++stats_.errors;
      error_ = "RTDE stream out of sync: a packet size of " + std::to_string(packet_size) +
               " bytes (valid: 3.." + std::to_string(max_packet_size_) + ") after " +
               std::to_string(stats_.packets) + " packets";
      stats_.discarded += static_cast<int64_t>(buffer_.size() - at);
      buffer_.clear();
      return false;
    }
    if (buffer_.size() - at < packet_size) break;
    RtdePacket packet;
    packet.type = static_cast<uint8_t>(buffer_[at + 2]);
    packet.payload = buffer_.substr(at + kRtdeHeaderSize, packet_size - kRtdeHeaderSize);
    out.push_back(std::move(packet));
    ++stats_.packets;
    at += packet_size;
  }
  buffer_.erase(0, at);
  return true;
}

void RtdeStreamReader::Reset() {
  buffer_.clear();
  corrupt_ = false;
  error_.clear();
}

}  // namespace recon::robot
