#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "devices/uwb/lec_format.h"
#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

/// Counters of what a LecLineParser has seen, for diagnostics and health displays. Every line
/// terminated by '\n' is counted exactly once in `lines` and in exactly one of `readings`,
/// `malformed` and `empty`, so lines == readings + malformed + empty always holds. Bytes after the
/// last '\n' are not counted until their line is terminated.
struct ParseStats {
  /// Complete lines seen (one per '\n'), including blank, prompt and overlong ones.
  int64_t lines = 0;
  /// Lines that produced a UwbReading, including the resynchronised ones.
  int64_t readings = 0;
  /// Lines dropped because they failed validation or overflowed kMaxLineBytes. A malformed line
  /// never contributes any value to a reading.
  int64_t malformed = 0;
  /// Blank lines and shell noise without data: prompts ("dwm> ") and echoes of a command we typed
  /// (e.g. "dwm> lec").
  int64_t empty = 0;
  /// Subset of `readings` recovered from a line with a garbled prefix (an interleaved echo such
  /// as "lePOS,..." or "dwm> lecDIST,..."). A rising rate means the link is overloaded.
  int64_t resynced = 0;
};

/// Parses exactly one `lec` (`DIST,...`) or `lep` (`POS,...`) line, without its terminator and
/// without resynchronisation. Returns nullopt unless every field count, number format and range
/// checks out; never returns a partially filled reading.
std::optional<UwbReading> ParseLecLine(std::string_view line);

/// Turns the DWM1001 shell's byte stream (from the serial driver or a simulated beacon) into
/// readings. Bytes may arrive in chunks of any size; lines end at '\n' and every '\r' is ignored,
/// so "\r\n" and stray carriage returns are tolerated. Pure: no I/O, no threads, no clock; the
/// caller timestamps readings. Not thread-safe: one parser per stream.
class LecLineParser {
 public:
  /// Longest line kept, in bytes (excluding '\r'). A real line has at most ~700; the bound keeps
  /// memory fixed when the stream loses its newlines (wrong baud rate, binary TLV mode).
  static constexpr size_t kMaxLineBytes = 4096;

  LecLineParser();

  /// Consumes `bytes` and appends one reading to `out` for each complete valid line (existing
  /// contents of `out` are kept). An incomplete trailing line is buffered for the next call.
  void Feed(std::string_view bytes, std::vector<UwbReading>& out);

  const ParseStats& stats() const { return stats_; }

 private:
  void EndLine(std::vector<UwbReading>& out);

  std::string line_;
  // True after the current line overflowed kMaxLineBytes: skip until the next '\n'.
  bool discarding_ = false;
  ParseStats stats_;
};

}  // namespace recon::uwb
