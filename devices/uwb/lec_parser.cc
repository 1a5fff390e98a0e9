#include "devices/uwb/lec_parser.h"

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

namespace recon::uwb {
namespace {

// DIST, n, n x (ANi, id, x, y, z, dist), POS, x, y, z, qf.
constexpr size_t kAnchorFields = 6;
constexpr size_t kPosFields = 5;
constexpr size_t kMaxFields = 2 + kAnchorFields * kMaxAnchors + kPosFields;

// The firmware prints millimetres as metres with exactly 2 decimals. Insisting on that shape (no
// exponent, no "nan"/"inf", no '+') is what exposes a field that lost a digit to interleaving,
// e.g. "0.00,0,AN3" seen at high rates: "0" would otherwise parse as a plausible value.
constexpr size_t kDecimals = 2;
constexpr size_t kMaxNumberChars = 16;

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

bool IsHexDigit(char c) { return IsDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }

// Splits at ','. Returns the field count, or 0 if there are more than kMaxFields fields (a line
// with that many cannot be valid, and the bound keeps the array fixed-size).
size_t SplitFields(std::string_view line, std::array<std::string_view, kMaxFields>& fields) {
  size_t count = 0;
  size_t start = 0;
  while (true) {
    if (count == kMaxFields) return 0;
    const size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      fields[count++] = line.substr(start);
      return count;
    }
    fields[count++] = line.substr(start, comma - start);
    start = comma + 1;
  }
}

// A value in metres: -?[0-9]+\.[0-9]{2}, finite and within kMaxAbsCoordinate_m.
bool ParseMetres(std::string_view field, double& value) {
  if (field.empty() || field.size() > kMaxNumberChars) return false;
  const size_t sign = field.front() == '-' ? 1 : 0;
  const size_t dot = field.find('.');
  if (dot == std::string_view::npos || dot == sign || field.size() - dot - 1 != kDecimals) {
    return false;
  }
  for (size_t i = sign; i < field.size(); ++i) {
    if (i != dot && !IsDigit(field[i])) return false;
  }
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value, std::chars_format::fixed);
  value += 0.0;  // The firmware prints "-0.00" for small negatives; downstream wants plain 0.
  return ec == std::errc() && ptr == end && std::isfinite(value) &&
         std::fabs(value) < kMaxAbsCoordinate_m;
}

// A plain decimal integer in [0, max]: digits only, at most 3 of them.
bool ParseSmallUint(std::string_view field, int max, int& value) {
  if (field.empty() || field.size() > 3) return false;
  for (const char c : field) {
    if (!IsDigit(c)) return false;
  }
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  return ec == std::errc() && ptr == end && value <= max;
}

// An anchor short address: 1-4 hex digits (the firmware prints 4, upper-case).
bool ParseAnchorId(std::string_view field, uint16_t& id) {
  if (field.empty() || field.size() > 4) return false;
  for (const char c : field) {
    if (!IsHexDigit(c)) return false;
  }
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, id, 16);
  return ec == std::errc() && ptr == end;
}

// "AN<index>" exactly: the firmware numbers anchors 0..n-1 in order, so a label out of sequence
// means two lines were spliced together.
bool IsAnchorLabel(std::string_view field, size_t index) {
  if (field.size() < 3 || field.substr(0, 2) != "AN") return false;
  size_t parsed = 0;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data() + 2, end, parsed);
  return ec == std::errc() && ptr == end && parsed == index &&
         (field.size() == 3 || field[2] != '0');
}

// Parses the 4 fields after "POS" into `reading`.
bool ParsePosition(const std::string_view* fields, UwbReading& reading) {
  if (!ParseMetres(fields[0], reading.x_m) || !ParseMetres(fields[1], reading.y_m) ||
      !ParseMetres(fields[2], reading.z_m) ||
      !ParseSmallUint(fields[3], kMaxQuality, reading.quality)) {
    return false;
  }
  reading.has_position = true;
  return true;
}

bool StartsWith(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

bool IsSpace(char c) { return c == ' ' || c == '\t'; }

// Blank lines, bare prompts and a prompt followed by the echo of a command we typed ("dwm> lec")
// carry no data and are normal shell traffic, so they must not inflate the malformed count.
bool IsBlankOrPrompt(std::string_view line) {
  auto trim_front = [&line] {
    while (!line.empty() && IsSpace(line.front())) line.remove_prefix(1);
  };
  trim_front();
  bool saw_prompt = false;
  while (StartsWith(line, "dwm>")) {
    line.remove_prefix(4);
    saw_prompt = true;
    trim_front();
  }
  while (!line.empty() && IsSpace(line.back())) line.remove_suffix(1);
  if (line.empty()) return true;
  if (!saw_prompt) return false;
  // Shell commands are lower-case words with optional numeric arguments; data lines always
  // contain upper-case letters and commas, so they can never match.
  for (const char c : line) {
    if (!((c >= 'a' && c <= 'z') || IsDigit(c) || IsSpace(c))) return false;
  }
  return true;
}

}  // namespace

std::optional<UwbReading> ParseLecLine(std::string_view line) {
  std::array<std::string_view, kMaxFields> fields;
  const size_t count = SplitFields(line, fields);
  if (count == 0) return std::nullopt;

  UwbReading reading;
  if (fields[0] == "POS") {
    if (count != kPosFields || !ParsePosition(&fields[1], reading)) return std::nullopt;
    return reading;
  }
  if (fields[0] != "DIST" || count < 2) return std::nullopt;

  int n = 0;
  if (!ParseSmallUint(fields[1], kMaxAnchors, n)) return std::nullopt;
  const size_t pos_index = 2 + kAnchorFields * static_cast<size_t>(n);
  const bool with_pos = count == pos_index + kPosFields;
  if (count != pos_index && !with_pos) return std::nullopt;

  reading.anchors.resize(static_cast<size_t>(n));
  for (size_t i = 0; i < reading.anchors.size(); ++i) {
    const std::string_view* f = &fields[2 + kAnchorFields * i];
    AnchorRange& anchor = reading.anchors[i];
    // The firmware's range is an unsigned millimetre count, so a negative one is garbage.
    if (!IsAnchorLabel(f[0], i) || !ParseAnchorId(f[1], anchor.id) ||
        !ParseMetres(f[2], anchor.x_m) || !ParseMetres(f[3], anchor.y_m) ||
        !ParseMetres(f[4], anchor.z_m) || !ParseMetres(f[5], anchor.distance_m) ||
        anchor.distance_m < 0.0) {
      return std::nullopt;
    }
  }
  if (with_pos && (fields[pos_index] != "POS" || !ParsePosition(&fields[pos_index + 1], reading))) {
    return std::nullopt;
  }
  return reading;
}

LecLineParser::LecLineParser() { line_.reserve(kMaxLineBytes); }

void LecLineParser::Feed(std::string_view bytes, std::vector<UwbReading>& out) {
  for (const char c : bytes) {
    if (c == '\r') continue;
    if (c == '\n') {
      EndLine(out);
      continue;
    }
    if (discarding_) continue;
    if (line_.size() == kMaxLineBytes) {
      discarding_ = true;
      line_.clear();
      continue;
    }
    line_.push_back(c);
  }
}

void LecLineParser::EndLine(std::vector<UwbReading>& out) {
  ++stats_.lines;
  const std::string_view line = line_;
  if (discarding_) {
    discarding_ = false;
    ++stats_.malformed;
  } else if (IsBlankOrPrompt(line)) {
    ++stats_.empty;
  } else if (StartsWith(line, "DIST,") || StartsWith(line, "POS,")) {
    // A line that starts cleanly but fails is not searched for an embedded "POS,": taking the tail
    // of a broken DIST line would be exactly the partial use we promise never to make.
    if (auto reading = ParseLecLine(line)) {
      out.push_back(std::move(*reading));
      ++stats_.readings;
    } else {
      ++stats_.malformed;
    }
  } else {
    // Garbled prefix (echo fragment, prompt, half a previous line): the real line is a suffix.
    // Try candidate starts from the earliest: if a whole "DIST,...,POS,..." line follows the
    // garbage, its own "POS," is a later candidate that would also parse, and taking it would
    // throw away the anchors. Any other later candidate lies inside the earlier valid line.
    bool recovered = false;
    for (size_t i = 1; i < line.size() && !recovered; ++i) {
      const std::string_view rest = line.substr(i);
      if (!StartsWith(rest, "DIST,") && !StartsWith(rest, "POS,")) continue;
      if (auto reading = ParseLecLine(rest)) {
        out.push_back(std::move(*reading));
        ++stats_.readings;
        ++stats_.resynced;
        recovered = true;
      }
    }
    if (!recovered) ++stats_.malformed;
  }
  line_.clear();
}

}  // namespace recon::uwb
