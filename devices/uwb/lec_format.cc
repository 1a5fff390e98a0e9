#include "devices/uwb/lec_format.h"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string_view>

namespace recon::uwb {
namespace {

// Values that would print as 10000.00 or more are rejected by the parser, so they must be
// rejected here too (rounding to 2 decimals can push 9999.996 over the limit).
constexpr double kMaxPrintable_m = kMaxAbsCoordinate_m - 0.005;

void CheckMetres(double value, std::string_view what) {
  if (!std::isfinite(value) || std::fabs(value) >= kMaxPrintable_m) {
    throw std::invalid_argument("DWM1001 line format: " + std::string(what) + " = " +
                                std::to_string(value) + " cannot be printed as the DWM1001 would");
  }
}

// Metres with 2 decimals. std::to_chars, unlike printf, ignores the C locale, so a German
// desktop cannot turn "1.50" into "1,50" and shift every field.
void AppendMetres(double value, std::string& out) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed, 2);
  std::string_view text(buffer, static_cast<size_t>(result.ptr - buffer));
  // The firmware formats integer millimetres, which have no negative zero.
  if (text == "-0.00") text = "0.00";
  out.append(text);
}

void AppendAnchorId(uint16_t id, std::string& out) {
  // Upper-case, as in every documented PANS output ("AN1,0CA8,...").
  static constexpr char kHex[] = "0123456789ABCDEF";
  for (int shift = 12; shift >= 0; shift -= 4) out.push_back(kHex[(id >> shift) & 0xF]);
}

void AppendPosition(const UwbReading& reading, std::string& out) {
  CheckMetres(reading.x_m, "x_m");
  CheckMetres(reading.y_m, "y_m");
  CheckMetres(reading.z_m, "z_m");
  if (reading.quality < 0 || reading.quality > kMaxQuality) {
    throw std::invalid_argument("DWM1001 line format: quality " + std::to_string(reading.quality) +
                                " is outside 0-100");
  }
  out.append("POS,");
  AppendMetres(reading.x_m, out);
  out.push_back(',');
  AppendMetres(reading.y_m, out);
  out.push_back(',');
  AppendMetres(reading.z_m, out);
  out.push_back(',');
  out.append(std::to_string(reading.quality));
}

}  // namespace

std::string FormatLecLine(const UwbReading& reading) {
  if (reading.anchors.size() > static_cast<size_t>(kMaxAnchors)) {
    throw std::invalid_argument("FormatLecLine: " + std::to_string(reading.anchors.size()) +
                                " anchors, at most " + std::to_string(kMaxAnchors));
  }
  std::string out = "DIST," + std::to_string(reading.anchors.size());
  for (size_t i = 0; i < reading.anchors.size(); ++i) {
    const AnchorRange& anchor = reading.anchors[i];
    CheckMetres(anchor.x_m, "anchor x_m");
    CheckMetres(anchor.y_m, "anchor y_m");
    CheckMetres(anchor.z_m, "anchor z_m");
    CheckMetres(anchor.distance_m, "anchor distance_m");
    // The firmware's range is unsigned; a simulator adding noise must clamp before printing.
    if (anchor.distance_m <= -0.005) {
      throw std::invalid_argument("FormatLecLine: negative anchor distance_m " +
                                  std::to_string(anchor.distance_m));
    }
    out.append(",AN" + std::to_string(i) + ",");
    AppendAnchorId(anchor.id, out);
    for (const double value : {anchor.x_m, anchor.y_m, anchor.z_m, anchor.distance_m}) {
      out.push_back(',');
      AppendMetres(value, out);
    }
  }
  if (reading.has_position) {
    out.push_back(',');
    AppendPosition(reading, out);
  }
  out.append("\r\n");
  return out;
}

std::string FormatLepLine(const UwbReading& reading) {
  if (!reading.has_position) {
    throw std::invalid_argument("FormatLepLine: the reading has no position");
  }
  std::string out;
  AppendPosition(reading, out);
  out.append("\r\n");
  return out;
}

}  // namespace recon::uwb
