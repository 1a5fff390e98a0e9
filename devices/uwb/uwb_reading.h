#pragma once

#include <cstdint>
#include <vector>

namespace recon::uwb {

/// Largest anchor count we accept in a `DIST` line. PANS tags range to at most 4 anchors, so
/// anything above 16 can only be a garbled count; the bound also caps per-line work.
inline constexpr int kMaxAnchors = 16;

/// Largest magnitude (exclusive) of a coordinate or distance, in metres. A UWB cell is tens of
/// metres across; values beyond this are garbled digits, not positions.
inline constexpr double kMaxAbsCoordinate_m = 1e4;

/// Largest location-engine quality factor the firmware reports.
inline constexpr int kMaxQuality = 100;

/// One anchor as the tag reports it in a `DIST` line: its 16-bit short address, its configured
/// position in the anchor frame and the measured range to it.
struct AnchorRange {
  uint16_t id = 0;
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
  double distance_m = 0.0;

  bool operator==(const AnchorRange&) const = default;
};

/// One update from a tag: the anchors it ranged to (empty for `lep` lines) and, when the location
/// engine has a fix, the estimated position in the anchor frame with its quality factor.
/// When has_position is false, x_m, y_m, z_m and quality are 0.
struct UwbReading {
  std::vector<AnchorRange> anchors;
  bool has_position = false;
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
  int quality = 0;  ///< 0-100, as reported by the firmware.

  bool operator==(const UwbReading&) const = default;
};

}  // namespace recon::uwb
