#include "app/cli/option_checks.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <thread>

#include "engine/core/strings.h"

namespace recon::cli {

namespace {

constexpr long long kIntMax = std::numeric_limits<int>::max();

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

CLI::Validator Make(double min, double max, bool whole, bool min_exclusive) {
  return CLI::Validator(
      [=](std::string& text) { return CheckNumber(text, min, max, whole, min_exclusive); },
      whole ? "INT" : "NUMBER");
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

long long ParallelismLimit() { return 4LL * std::max(1u, std::thread::hardware_concurrency()); }

CLI::Validator NumberBetween(double min, double max) { return Make(min, max, false, false); }
CLI::Validator PositiveNumber() {
  return Make(0, std::numeric_limits<double>::infinity(), false, true);
}
CLI::Validator PositiveNumberUpTo(double max) { return Make(0, max, false, true); }
CLI::Validator NonNegativeNumber() {
  return Make(0, std::numeric_limits<double>::infinity(), false, false);
}
CLI::Validator WholeBetween(long long min, long long max) {
  return Make(static_cast<double>(min), static_cast<double>(max), true, false);
}
CLI::Validator PositiveWhole() { return WholeBetween(1, kIntMax); }
CLI::Validator NonNegativeWhole() { return WholeBetween(0, kIntMax); }

}  // namespace recon::cli
