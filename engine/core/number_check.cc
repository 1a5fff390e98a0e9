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

// A plain decimal as a person types it: an optional sign, digits with at most one point, and an
// optional exponent ("-0.5", "3", ".5", "1e-3"). strtod also reads hexadecimal ("0x10" is 16),
// leading blanks and "infinity", none of which a person means as a count or a rate.
bool IsPlainDecimal(const std::string& text) {
  std::size_t i = 0;
  const auto digit = [&text](std::size_t k) {
    return k < text.size() && text[k] >= '0' && text[k] <= '9';
  };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t digits = 0;
  while (digit(i)) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (digit(i)) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  return i == text.size();
}

}  // namespace

std::string CheckNumber(const std::string& text, double min, double max, bool whole,
                        bool min_exclusive) {
  const std::string range = RangeText(min, max, whole, min_exclusive);
  const std::string got = " (got '" + text + "')";
  if (!IsPlainDecimal(text)) return range + got;
  errno = 0;  // a plain decimal is read whole; ERANGE says it is beyond a double
  const double value = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(value) || errno == ERANGE) return range + got;
  if (whole && value != std::floor(value)) return range + got;
  if (value < min || value > max || (min_exclusive && value <= min)) return range + got;
  return "";
}

}  // namespace recon
