#pragma once

#include <cmath>
#include <cstdint>

namespace recon {

/// A small, fast, portable random generator (xoshiro256** seeded through splitmix64).
/// We use our own instead of <random> distributions because the standard library's
/// distributions are implementation-defined: the same seed must give the same scenario, the
/// same images and the same batches on every platform, so every result can be reproduced
/// from the seed printed next to it.
class Rng {
 public:
  explicit Rng(uint64_t seed) { Seed(seed); }

  void Seed(uint64_t seed) {
    uint64_t z = seed;
    for (uint64_t& s : s_) s = SplitMix64(z);
    has_spare_normal_ = false;
  }

  /// Uniformly distributed 64-bit integer.
  uint64_t Next() {
    const uint64_t result = Rotl(s_[1] * 5, 7) * 9;
    const uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = Rotl(s_[3], 45);
    return result;
  }

  /// Uniform double in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

  /// Uniform double in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

  /// Uniform integer in [0, n). Uses rejection so there is no modulo bias.
  uint64_t UniformInt(uint64_t n) {
    const uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    uint64_t v;
    do {
      v = Next();
    } while (v >= limit);
    return v % n;
  }

  /// Standard normal sample (Box-Muller; the second value is kept for the next call).
  double Normal() {
    if (has_spare_normal_) {
      has_spare_normal_ = false;
      return spare_normal_;
    }
    double u1;
    do {
      u1 = Uniform();
    } while (u1 <= 0.0);
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * M_PI * u2;
    spare_normal_ = r * std::sin(angle);
    has_spare_normal_ = true;
    return r * std::cos(angle);
  }

  /// The full generator state, for checkpoints (resume continues the same stream).
  struct State {
    uint64_t s[4];
    bool has_spare_normal;
    double spare_normal;
  };
  State GetState() const { return {{s_[0], s_[1], s_[2], s_[3]}, has_spare_normal_, spare_normal_}; }
  void SetState(const State& state) {
    for (int i = 0; i < 4; ++i) s_[i] = state.s[i];
    has_spare_normal_ = state.has_spare_normal;
    spare_normal_ = state.spare_normal;
  }

  /// Derives an independent seed for a named sub-stream, so that e.g. the test scenarios of an
  /// experiment do not change when the number of training runs changes.
  static uint64_t Derive(uint64_t seed, uint64_t stream) {
    uint64_t z = seed ^ (0x9E3779B97F4A7C15ULL * (stream + 1));
    SplitMix64(z);
    return SplitMix64(z);
  }

 private:
  static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static uint64_t SplitMix64(uint64_t& state) {
    uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  uint64_t s_[4];
  bool has_spare_normal_ = false;
  double spare_normal_ = 0.0;
};

}  // namespace recon
