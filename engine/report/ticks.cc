#include "engine/report/ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace recon::report {
namespace {

// Tolerance, in units of one step or decade, for treating a bound as already on a tick, so that
// e.g. 10.000000000001 does not push the axis out by a whole step.
constexpr double kOnTick = 1e-9;

std::string Printf(const char* format, int decimals, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, decimals, value);
  std::string text = buffer;
  // Rounding can turn a tiny negative into "-0.00", which reads as a bug on an axis.
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) {
    text.erase(0, 1);
  }
  return text;
}

}  // namespace

double NiceStep(double raw_step) {
  if (!(raw_step > 0) || !std::isfinite(raw_step)) {
    throw std::invalid_argument("NiceStep needs a positive finite step");
  }
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw_step)));
  for (const double mantissa : {1.0, 2.0, 5.0, 10.0}) {
    if (mantissa * magnitude >= raw_step * (1 - kOnTick)) return mantissa * magnitude;
  }
  return 10 * magnitude;
}

AxisTicks LinearTicks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    throw std::invalid_argument("LinearTicks needs a finite range");
  }
  if (lo > hi) std::swap(lo, hi);
  if (lo == hi) {
    // A single value still deserves an axis around it.
    const double pad = lo == 0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  target_count = std::max(target_count, 1);
  AxisTicks ticks;
  ticks.step = NiceStep((hi - lo) / target_count);
  const double first = std::floor(lo / ticks.step + kOnTick);
  const double last = std::ceil(hi / ticks.step - kOnTick);
  ticks.lo = first * ticks.step;
  ticks.hi = last * ticks.step;
  for (double i = first; i <= last + 0.5; ++i) ticks.values.push_back(i * ticks.step);
  return ticks;
}

AxisTicks LogTicks(double lo, double hi) {
  if (!(lo > 0) || !(hi > 0) || !std::isfinite(lo) || !std::isfinite(hi)) {
    throw std::invalid_argument("LogTicks needs a positive finite range");
  }
  if (lo > hi) std::swap(lo, hi);
  int e_lo = static_cast<int>(std::floor(std::log10(lo) + kOnTick));
  int e_hi = static_cast<int>(std::ceil(std::log10(hi) - kOnTick));
  if (e_hi <= e_lo) e_hi = e_lo + 1;
  // Keep at most ~8 labelled decades so labels never crowd; a stride of k decades per tick.
  const int stride = std::max(1, (e_hi - e_lo + 7) / 8);
  e_hi = e_lo + stride * ((e_hi - e_lo + stride - 1) / stride);
  AxisTicks ticks;
  ticks.lo = std::pow(10.0, e_lo);
  ticks.hi = std::pow(10.0, e_hi);
  ticks.step = std::pow(10.0, stride);
  const bool fine = e_hi - e_lo <= 2;
  for (int e = e_lo; e <= e_hi; e += stride) {
    const double decade = std::pow(10.0, e);
    ticks.values.push_back(decade);
    if (fine && e < e_hi) {
      ticks.values.push_back(2 * decade);
      ticks.values.push_back(5 * decade);
    }
  }
  return ticks;
}

std::string FormatTick(double value, double step) {
  // Fixed decimals read best; only extreme magnitudes need exponents.
  if (std::abs(value) >= 1e7 || (step > 0 && step < 1e-5)) return Printf("%.*g", 4, value);
  const int decimals =
      step > 0 ? std::clamp(static_cast<int>(std::ceil(-std::log10(step) - kOnTick)), 0, 10) : 0;
  return Printf("%.*f", decimals, value);
}

bool UsePlainLogLabels(const AxisTicks& ticks) {
  return ticks.lo >= 1e-4 * (1 - kOnTick) && ticks.hi <= 1e5 * (1 + kOnTick);
}

std::string FormatLogTick(double value, bool plain) {
  if (!(value > 0)) return Printf("%.*g", 3, value);
  const int exponent = static_cast<int>(std::floor(std::log10(value) + kOnTick));
  if (plain) return Printf("%.*f", std::max(0, -exponent), value);
  const double mantissa = value / std::pow(10.0, exponent);
  char buffer[64];
  if (std::abs(mantissa - 1) < 1e-6) {
    std::snprintf(buffer, sizeof(buffer), "1e%d", exponent);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%.0fe%d", mantissa, exponent);
  }
  return buffer;
}

std::string FormatValue(double value, double largest_magnitude) {
  const double m = std::abs(largest_magnitude);
  int decimals = 2;
  if (m >= 1000) {
    decimals = 0;
  } else if (m >= 100) {
    decimals = 1;
  } else if (m > 0 && m < 1) {
    decimals = std::min(8, 1 - static_cast<int>(std::floor(std::log10(m))));
  }
  return Printf("%.*f", decimals, value);
}

}  // namespace recon::report
