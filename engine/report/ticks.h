#pragma once

#include <string>
#include <vector>

namespace recon::report {

/// Tick positions for one axis. `lo` and `hi` are the axis ends (themselves ticks), widened from
/// the data range to "nice" numbers so that the first and last tick sit on the axis ends.
struct AxisTicks {
  double lo = 0;
  double hi = 1;
  double step = 1;  ///< distance between ticks (linear axes); a factor of ten per decade (log)
  std::vector<double> values;
};

/// The smallest number of the form {1, 2, 5} x 10^k that is >= `raw_step` (> 0).
double NiceStep(double raw_step);

/// Ticks for a linear axis covering [lo, hi] with about `target_count` intervals. A degenerate
/// range (lo == hi) is widened around the value; non-finite input throws std::invalid_argument.
AxisTicks LinearTicks(double lo, double hi, int target_count = 6);

/// Ticks for a log axis covering [lo, hi] (both > 0): the ends are powers of ten. Short ranges
/// (up to two decades) also get ticks at 2x and 5x so the axis has more than two labels.
AxisTicks LogTicks(double lo, double hi);

/// Tick label for a linear axis: as many decimals as `step` needs, and "-0" printed as "0".
std::string FormatTick(double value, double step);

/// Tick label for a log axis: plain decimals ("0.001", "200") or exponent style ("1e-5",
/// "2e6"). One style should serve a whole axis; see UsePlainLogLabels.
std::string FormatLogTick(double value, bool plain);

/// True when every tick of a log axis reads well as a plain decimal (0.0001 to 100000).
bool UsePlainLogLabels(const AxisTicks& ticks);

/// A bar's value label: two decimals for values in [1, 100) like "16.82", fewer for large
/// magnitudes and more for small ones, chosen from the largest magnitude so all bars match.
std::string FormatValue(double value, double largest_magnitude);

}  // namespace recon::report
