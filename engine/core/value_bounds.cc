#include "engine/core/value_bounds.h"

#include <cmath>

#include "engine/core/strings.h"

namespace recon {

std::string OutOfBounds(const std::vector<ValueRange>& ranges, const std::vector<float>& values,
                        const char* field) {
  if (ranges.empty()) return "";
  for (size_t d = 0; d < values.size() && d < ranges.size(); ++d) {
    const ValueRange& r = ranges[d];
    const double v = values[d];
    // NaN fails both comparisons, so it is refused here too.
    if (v >= r.lo && v <= r.hi) continue;
    return std::string("field '") + field + "' dimension " + std::to_string(d) + " (" + r.what +
           ") is " + FormatNumber(v) + ", outside the physical range " + FormatNumber(r.lo) +
           " to " + FormatNumber(r.hi);
  }
  return "";
}

}  // namespace recon
