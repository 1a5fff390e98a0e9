#pragma once

// Checks for the numeric command-line options of `recon` and `recon-studio`, in place of CLI11's
// PositiveNumber / NonNegativeNumber / Range: these refuse NaN and infinity (CLI11's let NaN
// through, since every comparison with it is false), refuse a fraction or an out-of-range value
// for a whole-number option before CLI11 converts it (where it would say only "Could not
// convert"), and say the range in plain numbers (CLI11 prints 1.797...e308 as 309 digits).
// CLI11 puts the option's name in front: "--steps: must be a whole number from 1 to 2147483647
// (got 0)".

#include <CLI/CLI.hpp>
#include <string>

#include "engine/core/number_check.h"
#include "engine/worlds/world.h"

namespace recon::cli {

/// A finite number from `min` to `max` inclusive.
CLI::Validator NumberBetween(double min, double max);
/// A number > 0 and at most `max`. (There is no unbounded check: every number a person types
/// has a largest sensible value, and a typo beyond it is refused rather than run.)
CLI::Validator PositiveNumberUpTo(double max);
/// A whole number from `min` to `max` inclusive (an int option: at most 2147483647).
CLI::Validator WholeBetween(long long min, long long max);
/// A whole number from 1 to 2147483647 (a positive int option).
CLI::Validator PositiveWhole();
/// A whole number from 0 to 2147483647 (a non-negative int option).
CLI::Validator NonNegativeWhole();
/// A seed: a whole number from 0 to kMaxSeed. Without it a uint64 option reads "-1" as
/// 18446744073709551615 and runs.
CLI::Validator SeedNumber();

/// Upper bounds of the counts and sizes the commands take: far above any real use, low enough that
/// a typo (an extra zero or three) is refused in a second instead of running out of memory or
/// time. The same for `recon experiment`, `recon train` and `recon-studio`.
constexpr long long kMaxRuns = 1000;
constexpr long long kMaxTests = 100000;
constexpr long long kMaxDemos = 10000;
constexpr long long kMaxPlay = 100000;
constexpr long long kMaxSteps = 10000000;
constexpr long long kMaxBatch = 4096;
constexpr long long kMaxFeatureDim = 1024;
constexpr double kMaxLearningRate = 10.0;  ///< Adam diverges far below this
constexpr double kMaxTermWeight = 1000.0;  ///< a loss term's weight
constexpr long long kMaxImageSide = 8192;  ///< a rendered image's width or height (EGL limits)
/// 2^53: every seed up to it is exact in a double, so it reads back the same from any JSON
/// reader (results.csv and summary.json carry the seeds).
constexpr long long kMaxSeed = 9007199254740992LL;
/// DART noise on the executed joint velocities: the worlds' bound (ValidateExperimentConfig's).
constexpr double kMaxDemoNoise_rad_s = worlds::kMaxDemoNoise;
/// A simulated beacon's noise sigma (metres): the worlds' bound.
constexpr double kMaxBeaconNoise_m = worlds::kMaxBeaconNoise_m;
/// The studio's UI scale (--ui-scale): from a small laptop to a 4K screen seen from afar.
constexpr double kMinUiScale = 0.75;
constexpr double kMaxUiScale = 3.0;
/// The studio's countdown before a person's take (seconds): long enough to reach the keys.
constexpr double kMaxCountdown_s = 10.0;
/// A Dynamic 2D beacon's noise sigma (world units; the paper's are 2.5 to 6.5).
constexpr double kMaxDynamicNoise = 100.0;
constexpr double kMaxWaitSeconds = 7 * 24 * 3600.0;  ///< how long a command may be asked to run

/// The most threads or parallel jobs an option may ask for: 4 per core (at least 4).
long long ParallelismLimit();

/// The message a check gives for `text` ("" if it passes): recon::CheckNumber, here for tests.
using recon::CheckNumber;

}  // namespace recon::cli
