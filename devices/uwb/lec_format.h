#pragma once

#include <string>

#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

/// The line the PANS firmware prints for `lec`, including its "\r\n" terminator, so a simulated
/// beacon produces the same byte stream as a real one:
/// `DIST,<n>,AN0,<id>,<x>,<y>,<z>,<dist>,...[,POS,<x>,<y>,<z>,<qf>]`.
/// Values are printed in metres with 2 decimals; ids as 4 upper-case hex digits (e.g. "0CA8"),
/// as in the firmware's documented output. The POS part is present iff reading.has_position.
/// Throws std::invalid_argument if the reading cannot be printed as the firmware would (more
/// than kMaxAnchors anchors, a non-finite or out-of-range value, a negative distance, quality
/// outside 0-100): that is a bug in the producer, not something to round silently.
std::string FormatLecLine(const UwbReading& reading);

/// The line the PANS firmware prints for `lep`: `POS,<x>,<y>,<z>,<qf>\r\n`. Anchors are not part
/// of this format and are ignored. Throws std::invalid_argument if the reading has no position
/// or a value is out of range (see FormatLecLine).
std::string FormatLepLine(const UwbReading& reading);

}  // namespace recon::uwb
