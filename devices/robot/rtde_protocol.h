#pragma once

// Universal Robots' Real-Time Data Exchange (RTDE) wire format, protocol version 2: pure
// encoding and decoding, no sockets. Every packet is a big-endian u16 size (the 3-byte header
// included), a u8 type, then the payload; all numbers in payloads are big-endian.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace recon::robot {

/// RTDE packet types (the ASCII letter of each command).
enum class RtdePacketType : uint8_t {
  kRequestProtocolVersion = 'V',
  kGetControllerVersion = 'v',
  kTextMessage = 'M',
  kDataPackage = 'U',
  kSetupOutputs = 'O',
  kSetupInputs = 'I',
  kStart = 'S',
  kPause = 'P',
};

inline constexpr uint16_t kRtdeProtocolVersion = 2;
inline constexpr size_t kRtdeHeaderSize = 3;
/// Larger than any packet a controller sends for a sane recipe; a bigger size field means the
/// stream is not RTDE (or lost sync), not that a huge packet is coming.
inline constexpr size_t kRtdeMaxPacketSize = 4096;

/// One packet: its type and payload (the header stripped).
struct RtdePacket {
  uint8_t type = 0;
  std::string payload;
};

/// Header + payload, ready for the wire. Throws std::length_error past kRtdeMaxPacketSize.
std::string EncodeRtdePacket(uint8_t type, const std::string& payload);
inline std::string EncodeRtdePacket(RtdePacketType type, const std::string& payload = {}) {
  return EncodeRtdePacket(static_cast<uint8_t>(type), payload);
}

/// The field types of data packages.
enum class RtdeFieldType { kDouble, kVector6d, kVector3d, kInt32, kUint32, kUint64, kUint8, kBool };

/// E.g. "VECTOR6D" -> kVector6d; nullopt for NOT_FOUND, IN_USE or anything unknown.
std::optional<RtdeFieldType> ParseRtdeFieldType(const std::string& name);
std::string RtdeFieldTypeName(RtdeFieldType type);
/// Bytes on the wire: DOUBLE 8, VECTOR6D 48, VECTOR3D 24, INT32/UINT32 4, UINT64 8, UINT8/BOOL 1.
size_t RtdeFieldSize(RtdeFieldType type);

/// One field of a data package, typed as on the wire.
using RtdeValue = std::variant<double, std::array<double, 6>, std::array<double, 3>, int32_t,
                               uint32_t, uint64_t, uint8_t, bool>;

/// The controller's answer to a setup: the recipe id (0: refused) and the fields in order.
struct RtdeRecipe {
  uint8_t id = 0;
  std::vector<std::string> names;
  std::vector<RtdeFieldType> types;
  size_t PayloadSize() const;  ///< bytes after the recipe id
};

// ---- Requests (client -> controller) and replies (controller -> client) ----

std::string EncodeRequestProtocolVersion(uint16_t version);
std::optional<uint16_t> DecodeRequestProtocolVersion(const std::string& payload);
std::string EncodeAccepted(RtdePacketType type, bool accepted);  ///< 'V', 'S', 'P' replies
std::optional<bool> DecodeAccepted(const std::string& payload);

struct RtdeControllerVersion {
  uint32_t major = 0, minor = 0, bugfix = 0, build = 0;
  std::string ToString() const;  ///< "5.11.0.108"
};
std::string EncodeControllerVersion(const RtdeControllerVersion& version);
std::optional<RtdeControllerVersion> DecodeControllerVersion(const std::string& payload);

std::string EncodeSetupOutputs(double frequency_hz, const std::vector<std::string>& names);
struct RtdeSetupOutputsRequest {
  double frequency_hz = 0;
  std::vector<std::string> names;
};
std::optional<RtdeSetupOutputsRequest> DecodeSetupOutputs(const std::string& payload);
/// The reply: recipe id + comma-separated type names (NOT_FOUND for unknown names).
std::string EncodeSetupOutputsReply(uint8_t recipe_id, const std::vector<std::string>& types);
struct RtdeSetupOutputsReply {
  uint8_t recipe_id = 0;
  std::vector<std::string> types;  ///< as sent, e.g. "VECTOR6D" or "NOT_FOUND"
};
std::optional<RtdeSetupOutputsReply> DecodeSetupOutputsReply(const std::string& payload);

/// Protocol 2 text message: u8 length + message, u8 length + source, u8 warning level.
struct RtdeTextMessage {
  std::string message;
  std::string source;
  uint8_t level = 0;  ///< 0 exception, 1 error, 2 warning, 3 info
};
std::string EncodeTextMessage(const RtdeTextMessage& message);
std::optional<RtdeTextMessage> DecodeTextMessage(const std::string& payload);

/// A data package: recipe id, then `values` packed in recipe order. Throws std::invalid_argument
/// when a value's type does not match the recipe (a bug in the caller, not bad input).
std::string PackDataPackage(const RtdeRecipe& recipe, const std::vector<RtdeValue>& values);
/// Unpacks a 'U' payload against `recipe`. nullopt (with `why`) when the recipe id differs or the
/// size is not exactly what the recipe says; never reads past the payload.
std::optional<std::vector<RtdeValue>> UnpackDataPackage(const RtdeRecipe& recipe,
                                                        const std::string& payload,
                                                        std::string* why = nullptr);

/// Counters of an RtdeStreamReader.
struct RtdeStreamStats {
  int64_t bytes = 0;      ///< bytes fed, including any discarded after corruption
  int64_t packets = 0;    ///< whole packets delivered
  int64_t errors = 0;     ///< protocol errors (a bad size field); at most one per corruption
  int64_t discarded = 0;  ///< bytes ignored because the stream was corrupt
};

/// Splits a byte stream into packets, whatever the chunking (one byte at a time or many packets
/// at once). RTDE has no sync marker: once a size field is impossible (< 3 or > the maximum) no
/// later byte can be trusted, so the reader declares the stream corrupt, counts one error,
/// ignores everything after it and keeps the reason; the owner should drop the connection. Reset()
/// starts over (a new connection).
class RtdeStreamReader {
 public:
  explicit RtdeStreamReader(size_t max_packet_size = kRtdeMaxPacketSize);
  /// Appends the packets completed by these bytes to `out`. False once the stream is corrupt.
  bool Feed(const char* data, size_t size, std::vector<RtdePacket>& out);
  bool Feed(const std::string& bytes, std::vector<RtdePacket>& out) {
    return Feed(bytes.data(), bytes.size(), out);
  }
  void Reset();

  bool corrupt() const { return corrupt_; }
  const std::string& error() const { return error_; }
  const RtdeStreamStats& stats() const { return stats_; }
  /// Bytes of an incomplete packet waiting for the rest.
  size_t pending() const { return buffer_.size(); }

 private:
  size_t max_packet_size_;
  std::string buffer_;
  bool corrupt_ = false;
  std::string error_;
  RtdeStreamStats stats_;
};

}  // namespace recon::robot
