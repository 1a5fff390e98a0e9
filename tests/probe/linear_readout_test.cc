#include "engine/probe/linear_readout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::probe {
namespace {

TEST(LinearReadoutTest, AFeatureThatIsThePositionReadsOutWithR2OfOneAndNoiseWithNone) {
  Rng rng(21);
  std::vector<std::vector<float>> features;
  std::vector<std::vector<double>> position, unrelated;
  for (int i = 0; i < 200; ++i) {
    const double x = rng.Uniform(0.2, 0.8), y = rng.Uniform(-0.5, 0.5);
    // phi holds the position mixed linearly with offsets, and two unrelated channels.
    features.push_back({static_cast<float>(3 * x - y + 1), static_cast<float>(x + 2 * y),
                        static_cast<float>(rng.Normal()), static_cast<float>(rng.Normal())});
    position.push_back({x, y});
    unrelated.push_back({rng.Uniform(0, 1), rng.Uniform(0, 1)});
  }
  const ReadoutScore encoded = FitLinearReadout(features, position);
  EXPECT_GT(encoded.r2, 0.999);
  ASSERT_EQ(encoded.r2_per_dimension.size(), 2u);
  EXPECT_GT(encoded.r2_per_dimension[1], 0.999);
  EXPECT_EQ(encoded.held_out, 50);
  EXPECT_EQ(encoded.fitted, 150);
  const ReadoutScore not_encoded = FitLinearReadout(features, unrelated);
  EXPECT_LT(not_encoded.r2, 0.1);
}

TEST(LinearReadoutTest, RefusesMismatchedOrTooFewFrames) {
  EXPECT_THROW(FitLinearReadout({{1}, {2}}, {{1}}), UserError);
  EXPECT_THROW(FitLinearReadout({{1}, {2}, {3}}, {{1}, {2}, {3}}), UserError);
  EXPECT_THROW(FitLinearReadout({{1}, {2, 3}, {3}, {4}, {5}, {6}, {7}, {8}},
                                {{1}, {2}, {3}, {4}, {5}, {6}, {7}, {8}}),
               UserError);
}

}  // namespace
}  // namespace recon::probe
