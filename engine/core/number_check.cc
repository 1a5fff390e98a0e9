#include "engine/core/number_check.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "engine/core/strings.h"

namespace recon {

namespace {

std::string RangeText(double min, double max, bool whole, bool min_exclusive) {
  // Whole bounds in full digits (2147483647, not 2.14748e+09).
  const auto text = [whole](double v) {
    return whole ? std::to_string(static_cast<long long>(v)) : FormatNumber(v);
  };
  const std::string kind = whole ? "a whole number" : "a number";
  const bool unbounded = max == std::numeric_limits<double>::infinity();
  if (min_exclusive && unbounded) return "must be " + kind + " > " + text(min);
  if (min_exclusive) return "must be " + kind + " > " + text(min) + " and at most " + text(max);
  if (unbounded) return "must be " + kind + " >= " + text(min);
  return "must be " + kind + " from " + text(min) + " to " + text(max);
}

}  // namespace

std::string CheckNumber(const std::string& text, double min, double max, bool whole,
                        bool min_exclusive) {
  const std::string range = RangeText(min, max, whole, min_exclusive);
  const std::string got = " (got '" + text + "')";
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0') return range + got;
  if (!std::isfinite(value) || errno == ERANGE) return range + got;
  if (whole && value != std::floor(value)) return range + got;
  if (value < min || value > max || (min_exclusive && value <= min)) return range + got;
  return "";
}

}  // namespace recon
