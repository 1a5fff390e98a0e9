#include "devices/uwb/tlv_codec.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace recon::uwb {
namespace {

// The firmware reports millimetres; anything at or beyond kMaxAbsCoordinate_m is garbled (the
// same bound the lec parser applies to the text form).
constexpr int64_t kMaxAbsMillimetres = static_cast<int64_t>(kMaxAbsCoordinate_m * 1000.0);
// Feed works through its input in slices so the buffer stays small whatever the chunk size.
constexpr size_t kSliceBytes = 512;

void PutU16(uint32_t v, std::string& out) {
  out.push_back(static_cast<char>(v & 0xFF));
  out.push_back(static_cast<char>((v >> 8) & 0xFF));
}

void PutU32(uint32_t v, std::string& out) {
  PutU16(v & 0xFFFF, out);
  PutU16(v >> 16, out);
}

int32_t ToMillimetres(double metres, const char* what) {
  if (!std::isfinite(metres) || std::fabs(metres) * 1000.0 >= kMaxAbsMillimetres - 0.5) {
    throw std::invalid_argument(std::string("DWM1001 TLV: ") + what + " = " +
                                std::to_string(metres) + " m cannot be sent as the DWM1001 would");
  }
  return static_cast<int32_t>(std::llround(metres * 1000.0));
}

void PutPosition(double x_m, double y_m, double z_m, int quality, std::string& out) {
  if (quality < 0 || quality > kMaxQuality) {
    throw std::invalid_argument("DWM1001 TLV: quality " + std::to_string(quality) +
                                " is outside 0-100");
  }
  for (const auto& [value, what] : {std::pair{x_m, "x_m"}, {y_m, "y_m"}, {z_m, "z_m"}}) {
    PutU32(static_cast<uint32_t>(ToMillimetres(value, what)), out);
  }
  out.push_back(static_cast<char>(quality));
}

uint32_t GetU32(const unsigned char* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
         static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

// A millimetre coordinate as metres; false if it is out of range.
bool GetMetres(const unsigned char* p, double& metres) {
  const int64_t mm = static_cast<int32_t>(GetU32(p));
  if (mm <= -kMaxAbsMillimetres || mm >= kMaxAbsMillimetres) return false;
  metres = static_cast<double>(mm) / 1000.0;
  return true;
}

// 13 bytes: x, y, z, quality.
bool GetPosition(const unsigned char* p, double& x_m, double& y_m, double& z_m, int& quality) {
  quality = p[12];
  return GetMetres(p, x_m) && GetMetres(p + 4, y_m) && GetMetres(p + 8, z_m) &&
         quality <= kMaxQuality;
}

}  // namespace

std::string EncodePosGet() { return {static_cast<char>(tlv::kPosGet), 0}; }
std::string EncodeLocGet() { return {static_cast<char>(tlv::kLocGet), 0}; }
std::string EncodeNodeIdGet() { return {static_cast<char>(tlv::kNodeIdGet), 0}; }

std::string EncodeUpdRateSet(int active_100ms, int stationary_100ms) {
  for (const int v : {active_100ms, stationary_100ms}) {
    if (v < 1 || v > 600) {
      throw std::invalid_argument("upd_rate_set: " + std::to_string(v) +
                                  " x 100 ms is outside 1-600");
    }
  }
  std::string out = {static_cast<char>(tlv::kUpdRateSet), 4};
  PutU16(static_cast<uint32_t>(active_100ms), out);
  PutU16(static_cast<uint32_t>(stationary_100ms), out);
  return out;
}

std::string EncodeStatus(int error) {
  if (error < 0 || error >= tlv::kErrorCodes) {
    throw std::invalid_argument("DWM1001 TLV: error code " + std::to_string(error));
  }
  return {static_cast<char>(tlv::kStatus), 1, static_cast<char>(error)};
}

std::string EncodePosition(const UwbReading& reading) {
  std::string out = {static_cast<char>(tlv::kPosition), static_cast<char>(tlv::kPositionBytes)};
  PutPosition(reading.x_m, reading.y_m, reading.z_m, reading.quality, out);
  return out;
}

std::string EncodeAnchorList(const std::vector<AnchorRange>& anchors) {
  if (anchors.size() > static_cast<size_t>(tlv::kMaxListedAnchors)) {
    throw std::invalid_argument("DWM1001 TLV: " + std::to_string(anchors.size()) +
                                " anchors, at most " + std::to_string(tlv::kMaxListedAnchors));
  }
  std::string out = {static_cast<char>(tlv::kAnchorList),
                     static_cast<char>(1 + tlv::kAnchorBytes * anchors.size()),
                     static_cast<char>(anchors.size())};
  for (const AnchorRange& a : anchors) {
    if (!(a.distance_m >= 0.0)) {
      throw std::invalid_argument("DWM1001 TLV: anchor distance " + std::to_string(a.distance_m));
    }
    PutU16(a.id, out);
    PutU32(static_cast<uint32_t>(ToMillimetres(a.distance_m, "anchor distance_m")), out);
    out.push_back(static_cast<char>(kMaxQuality));  // ranging quality: not modelled
    PutPosition(a.x_m, a.y_m, a.z_m, kMaxQuality, out);
  }
  return out;
}

std::string EncodeNodeId(uint64_t node_id) {
  std::string out = {static_cast<char>(tlv::kNodeId), 8};
  PutU32(static_cast<uint32_t>(node_id), out);
  PutU32(static_cast<uint32_t>(node_id >> 32), out);
  return out;
}

TlvResponseParser::TlvResponseParser() { buffer_.reserve(tlv::kMaxFrameBytes + kSliceBytes); }

void TlvResponseParser::Feed(std::string_view bytes, std::vector<TlvFrame>& out) {
  stats_.bytes += static_cast<int64_t>(bytes.size());
  while (!bytes.empty()) {
    const size_t take = std::min(bytes.size(), kSliceBytes);
    buffer_.append(bytes.substr(0, take));
    bytes.remove_prefix(take);
    size_t consumed = 0;
    while (consumed < buffer_.size()) {
      const int result =
          TryFrame(std::string_view(buffer_).substr(consumed, tlv::kMaxFrameBytes), out);
      if (result == 0) break;
      if (result > 0) {
        consumed += static_cast<size_t>(result);
        stats_.frame_bytes += result;
        dropping_ = false;
      } else {
        consumed += 1;
        Drop(1);
      }
    }
    buffer_.erase(0, consumed);
  }
}

void TlvResponseParser::Drop(size_t n) {
  stats_.dropped_bytes += static_cast<int64_t>(n);
  if (!dropping_) ++stats_.garbage_runs;
  dropping_ = true;
  in_response_ = false;
}

int TlvResponseParser::TryFrame(std::string_view bytes, std::vector<TlvFrame>& out) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t size = bytes.size();
  if (size == 0) return 0;
  const uint8_t type = p[0];
  const bool value_frame =
      type == tlv::kPosition || type == tlv::kAnchorList || type == tlv::kNodeId;
  if (type != tlv::kStatus && !(in_response_ && value_frame)) return -1;
  if (size < 2) return 0;
  const size_t length = p[1];
  // Each type has a fixed layout; a length that does not match it is a garbled frame, and
  // checking it first means no value is ever read beyond what the frame holds.
  bool length_ok = false;
  switch (type) {
    case tlv::kStatus:
      length_ok = length == 1;
      break;
    case tlv::kPosition:
      length_ok = length == tlv::kPositionBytes;
      break;
    case tlv::kNodeId:
      length_ok = length == 8;
      break;
    default:  // anchor list
      length_ok = length >= 1 && (length - 1) % tlv::kAnchorBytes == 0;
  }
  if (!length_ok) {
    ++stats_.rejected;
    return -1;
  }
  if (size < 2 + length) return 0;
  const unsigned char* value = p + 2;
  TlvFrame frame;
  bool valid = true;
  switch (type) {
    case tlv::kStatus:
      frame.kind = TlvFrame::Kind::kStatus;
      frame.error = value[0];
      valid = frame.error < tlv::kErrorCodes;
      break;
    case tlv::kPosition: {
      frame.kind = TlvFrame::Kind::kPosition;
      UwbReading& r = frame.reading;
      valid = GetPosition(value, r.x_m, r.y_m, r.z_m, r.quality);
      r.has_position = valid;
      break;
    }
    case tlv::kNodeId:
      frame.kind = TlvFrame::Kind::kNodeId;
      frame.node_id =
          static_cast<uint64_t>(GetU32(value)) | static_cast<uint64_t>(GetU32(value + 4)) << 32;
      break;
    default: {
      frame.kind = TlvFrame::Kind::kAnchorList;
      const size_t count = value[0];
      valid = count == (length - 1) / tlv::kAnchorBytes;
      for (size_t i = 0; valid && i < count; ++i) {
        const unsigned char* a = value + 1 + i * tlv::kAnchorBytes;
        AnchorRange anchor;
        anchor.id = static_cast<uint16_t>(a[0] | a[1] << 8);
        const uint32_t distance_mm = GetU32(a + 2);
        int range_quality = a[6];
        int position_quality = 0;
        valid = distance_mm < kMaxAbsMillimetres && range_quality <= kMaxQuality &&
                GetPosition(a + 7, anchor.x_m, anchor.y_m, anchor.z_m, position_quality);
        anchor.distance_m = distance_mm / 1000.0;
        frame.reading.anchors.push_back(anchor);
      }
    }
  }
  if (!valid) {
    ++stats_.rejected;
    return -1;
  }
  if (frame.kind == TlvFrame::Kind::kStatus) {
    ++stats_.status_by_code[static_cast<size_t>(frame.error)];
    in_response_ = frame.error == tlv::kOk;
  }
  if (frame.kind == TlvFrame::Kind::kPosition) ++stats_.readings;
  ++stats_.frames;
  out.push_back(std::move(frame));
  return static_cast<int>(2 + length);
}

}  // namespace recon::uwb
