#include "engine/core/stats.h"

#include <gtest/gtest.h>

#include <cmath>

namespace recon {
namespace {

TEST(StatsTest, MeanAndStandardError) {
  const std::vector<double> v = {1, 2, 3, 4};
  EXPECT_DOUBLE_EQ(Mean(v), 2.5);
  // sample sd = sqrt(5/3); sem = sd / 2
  EXPECT_NEAR(StandardError(v), std::sqrt(5.0 / 3.0) / 2.0, 1e-12);
  EXPECT_EQ(StandardError({3.0}), 0.0);
  EXPECT_EQ(Mean({}), 0.0);
}

}  // namespace
}  // namespace recon
