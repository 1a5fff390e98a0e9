#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

/// Type bytes of the DWM1001 PANS TLV API (REFERENCE.md section 4). Every value is little-endian.
namespace tlv {
inline constexpr uint8_t kPosGet = 0x02;      ///< request: the tag's position
inline constexpr uint8_t kUpdRateSet = 0x03;  ///< request: two u16 update periods, 100 ms units
inline constexpr uint8_t kLocGet = 0x0C;      ///< request: position and the anchors ranged to
inline constexpr uint8_t kNodeIdGet = 0x30;   ///< request: the 64-bit node id
inline constexpr uint8_t kStatus = 0x40;      ///< response: 0x40 0x01 <error code>
inline constexpr uint8_t kPosition = 0x41;    ///< response: x, y, z int32 mm + u8 quality
inline constexpr uint8_t kAnchorList = 0x49;  ///< response: u8 count, then count x 20 bytes
inline constexpr uint8_t kNodeId = 0x4A;      ///< response: u64 node id

/// Error codes of a status response.
inline constexpr int kOk = 0;
inline constexpr int kUnknownTlv = 1;  ///< unknown type or broken TLV (also a stray byte)
inline constexpr int kInternal = 2;
inline constexpr int kInvalidParameter = 3;
inline constexpr int kBusy = 4;
inline constexpr int kNotPermitted = 5;
inline constexpr int kErrorCodes = 6;

inline constexpr size_t kPositionBytes = 13;  ///< 3 x int32 mm + u8 quality
inline constexpr size_t kAnchorBytes = 20;    ///< u16 address, u32 mm, u8 quality, position
/// The length byte is a u8, so one anchor list holds at most (255 - 1) / 20 anchors.
inline constexpr int kMaxListedAnchors = 12;
/// Longest TLV (type, length, 255 value bytes).
inline constexpr size_t kMaxFrameBytes = 2 + 255;
}  // namespace tlv

/// Requests the host sends, as raw bytes.
std::string EncodePosGet();
std::string EncodeLocGet();
std::string EncodeNodeIdGet();
/// upd_rate_set: the update period while moving and while stationary, in 100 ms units (1-600,
/// as the firmware accepts). Throws std::invalid_argument outside that range.
std::string EncodeUpdRateSet(int active_100ms, int stationary_100ms);

/// Responses the firmware sends, for the fake beacon and for tests. The position and anchors must
/// be printable as the firmware would (finite, within kMaxAbsCoordinate_m, quality 0-100, at most
/// kMaxListedAnchors anchors, non-negative distances); otherwise std::invalid_argument.
std::string EncodeStatus(int error);
std::string EncodePosition(const UwbReading& reading);
std::string EncodeAnchorList(const std::vector<AnchorRange>& anchors);
std::string EncodeNodeId(uint64_t node_id);

/// One complete TLV of a response. A response is a status frame followed, when its error is 0, by
/// the value frames of the request (pos_get: a position; loc_get: a position and, on a tag, an
/// anchor list; node_id_get: a node id). The parser delivers each frame as soon as it is complete,
/// so a caller never waits for the next response to learn that one has ended.
struct TlvFrame {
  enum class Kind { kStatus, kPosition, kAnchorList, kNodeId };
  Kind kind = Kind::kStatus;
  int error = 0;  ///< kStatus: the error code (tlv::kOk ... tlv::kNotPermitted)
  /// kPosition: has_position, x_m, y_m, z_m, quality. kAnchorList: anchors (id, position,
  /// distance; the per-anchor quality factors are not kept).
  UwbReading reading;
  uint64_t node_id = 0;  ///< kNodeId
};

/// Counters of what a TlvResponseParser has seen. Every byte fed is accounted for exactly once:
/// bytes == frame_bytes + dropped_bytes + TlvResponseParser::pending_bytes().
struct TlvParseStats {
  int64_t bytes = 0;        ///< bytes fed
  int64_t frame_bytes = 0;  ///< bytes of the frames delivered
  /// Bytes skipped while resynchronising: garbage, echoes, frames of unknown types, frames with a
  /// wrong length or values out of range (the firmware never sends those, so they are garbled).
  int64_t dropped_bytes = 0;
  int64_t frames = 0;    ///< frames delivered (of any kind)
  int64_t readings = 0;  ///< position frames delivered
  /// Well-delimited frames rejected for their content (length or range); their bytes are dropped.
  int64_t rejected = 0;
  /// Runs of consecutive dropped bytes: each is one garbled stretch the parser skipped.
  int64_t garbage_runs = 0;
  /// Status frames by error code; status_by_code[0] counts the successes.
  std::array<int64_t, tlv::kErrorCodes> status_by_code{};
};

/// Turns the bytes a DWM1001 sends in TLV mode into frames. Bytes may arrive in any chunking.
/// Resynchronises after garbage: a response always starts 0x40 0x01 <error 0-5>, and value frames
/// (0x41, 0x49, 0x4A) are only accepted after a successful status, so a byte that cannot start a
/// frame there is dropped (and counted) and the next byte tried. Lengths come from the wire and
/// are checked against each type's fixed layout before any value is read. The buffer holds at
/// most one incomplete frame (< tlv::kMaxFrameBytes). Pure: no I/O, threads or clock. Not
/// thread-safe: one parser per stream.
class TlvResponseParser {
 public:
  TlvResponseParser();

  /// Consumes `bytes`, appending each complete valid frame to `out` (existing contents kept).
  void Feed(std::string_view bytes, std::vector<TlvFrame>& out);

  const TlvParseStats& stats() const { return stats_; }
  /// Bytes of an incomplete frame waiting for the rest.
  size_t pending_bytes() const { return buffer_.size(); }

 private:
  // What `bytes` starts with: 0 need more bytes, > 0 a frame of that many bytes was delivered,
  // < 0 the first byte cannot start a valid frame.
  int TryFrame(std::string_view bytes, std::vector<TlvFrame>& out);
  void Drop(size_t n);

  std::string buffer_;
  // After a successful status, value frames of the same response may follow.
  bool in_response_ = false;
  // The last byte consumed was dropped: further drops extend the same garbage run.
  bool dropping_ = false;
  TlvParseStats stats_;
};

}  // namespace recon::uwb
