#include "app/cli/option_checks.h"

#include <algorithm>
#include <limits>
#include <string>
#include <thread>

#include "engine/core/number_check.h"

namespace recon::cli {

namespace {

constexpr long long kIntMax = std::numeric_limits<int>::max();

CLI::Validator Make(double min, double max, bool whole, bool min_exclusive) {
  return CLI::Validator(
      [=](std::string& text) { return CheckNumber(text, min, max, whole, min_exclusive); },
      whole ? "INT" : "NUMBER");
}

}  // namespace

long long ParallelismLimit() { return 4LL * std::max(1u, std::thread::hardware_concurrency()); }

CLI::Validator NumberBetween(double min, double max) { return Make(min, max, false, false); }
CLI::Validator PositiveNumberUpTo(double max) { return Make(0, max, false, true); }
CLI::Validator WholeBetween(long long min, long long max) {
  return Make(static_cast<double>(min), static_cast<double>(max), true, false);
}
CLI::Validator PositiveWhole() { return WholeBetween(1, kIntMax); }
CLI::Validator NonNegativeWhole() { return WholeBetween(0, kIntMax); }
CLI::Validator SeedNumber() { return WholeBetween(0, kMaxSeed); }

}  // namespace recon::cli
