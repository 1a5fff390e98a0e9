#include "engine/core/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace recon {
namespace {

TEST(RngTest, SameSeedSameStream) {
  Rng a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const uint64_t va = a.Next();
    EXPECT_EQ(va, b.Next());
    EXPECT_NE(va, c.Next());
  }
}

TEST(RngTest, UniformAndNormalMoments) {
  Rng rng(7);
  constexpr int kN = 200000;
  double sum_u = 0, sum_n = 0, sum_n2 = 0;
  for (int i = 0; i < kN; ++i) {
    const double u = rng.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum_u += u;
    const double n = rng.Normal();
    sum_n += n;
    sum_n2 += n * n;
  }
  EXPECT_NEAR(sum_u / kN, 0.5, 0.005);
  EXPECT_NEAR(sum_n / kN, 0.0, 0.01);
  EXPECT_NEAR(sum_n2 / kN, 1.0, 0.02);
}

TEST(RngTest, UniformIntCoversRangeEvenly) {
  Rng rng(3);
  std::vector<int> counts(3, 0);
  for (int i = 0; i < 30000; ++i) counts[rng.UniformInt(3)]++;
  for (int c : counts) EXPECT_NEAR(c, 10000, 400);
}

TEST(RngTest, StateRoundTripContinuesTheStream) {
  Rng a(5);
  a.Normal();  // leaves a spare normal in the state
  const Rng::State state = a.GetState();
  const double expected = a.Normal();
  Rng b(999);
  b.SetState(state);
  EXPECT_EQ(b.Normal(), expected);
}

TEST(RngTest, DerivedSeedsDiffer) {
  EXPECT_NE(Rng::Derive(1, 0), Rng::Derive(1, 1));
  EXPECT_NE(Rng::Derive(1, 0), Rng::Derive(2, 0));
  EXPECT_EQ(Rng::Derive(1, 0), Rng::Derive(1, 0));
}

}  // namespace
}  // namespace recon
