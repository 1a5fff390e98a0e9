#include "engine/report/ticks.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace recon::report {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;

TEST(TicksTest, NiceStepRoundsUpToOneTwoFive) {
  EXPECT_DOUBLE_EQ(NiceStep(0.7), 1);
  EXPECT_DOUBLE_EQ(NiceStep(1), 1);
  EXPECT_DOUBLE_EQ(NiceStep(1.2), 2);
  EXPECT_DOUBLE_EQ(NiceStep(3), 5);
  EXPECT_DOUBLE_EQ(NiceStep(7), 10);
  EXPECT_DOUBLE_EQ(NiceStep(0.013), 0.02);
  EXPECT_DOUBLE_EQ(NiceStep(2500), 5000);
  EXPECT_THROW(NiceStep(0), std::invalid_argument);
}

TEST(TicksTest, LinearTicksWidenToNiceEnds) {
  const AxisTicks ticks = LinearTicks(12.7, 17.8, 6);
  EXPECT_DOUBLE_EQ(ticks.step, 1);
  EXPECT_DOUBLE_EQ(ticks.lo, 12);
  EXPECT_DOUBLE_EQ(ticks.hi, 18);
  EXPECT_THAT(ticks.values, ElementsAre(12, 13, 14, 15, 16, 17, 18));
}

TEST(TicksTest, LinearTicksOnSeveralRanges) {
  const AxisTicks unit = LinearTicks(0, 1, 5);
  EXPECT_DOUBLE_EQ(unit.step, 0.2);
  EXPECT_THAT(unit.values,
              ElementsAre(DoubleNear(0, 1e-12), DoubleNear(0.2, 1e-12), DoubleNear(0.4, 1e-12),
                          DoubleNear(0.6, 1e-12), DoubleNear(0.8, 1e-12), DoubleNear(1, 1e-12)));

  const AxisTicks crossing = LinearTicks(-3.2, 4.1, 6);
  EXPECT_DOUBLE_EQ(crossing.step, 2);
  EXPECT_DOUBLE_EQ(crossing.lo, -4);
  EXPECT_DOUBLE_EQ(crossing.hi, 6);

  const AxisTicks steps = LinearTicks(0, 5999, 6);
  EXPECT_DOUBLE_EQ(steps.step, 1000);
  EXPECT_DOUBLE_EQ(steps.hi, 6000);
  EXPECT_EQ(steps.values.size(), 7u);

  const AxisTicks small = LinearTicks(0.00123, 0.00187, 4);
  EXPECT_DOUBLE_EQ(small.step, 0.0002);
  EXPECT_NEAR(small.lo, 0.0012, 1e-15);
  EXPECT_NEAR(small.hi, 0.0020, 1e-15);
}

TEST(TicksTest, LinearTicksHandleDegenerateAndBadRanges) {
  const AxisTicks single = LinearTicks(5, 5);
  EXPECT_LT(single.lo, 5);
  EXPECT_GT(single.hi, 5);
  const AxisTicks zero = LinearTicks(0, 0);
  EXPECT_LT(zero.lo, zero.hi);
  const AxisTicks reversed = LinearTicks(10, 0, 5);
  EXPECT_DOUBLE_EQ(reversed.lo, 0);
  EXPECT_DOUBLE_EQ(reversed.hi, 10);
  EXPECT_THROW(LinearTicks(std::nan(""), 1), std::invalid_argument);
  EXPECT_THROW(LinearTicks(0, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(TicksTest, LogTicksAtDecades) {
  const AxisTicks loss = LogTicks(0.0012, 8.5);
  EXPECT_DOUBLE_EQ(loss.lo, 0.001);
  EXPECT_DOUBLE_EQ(loss.hi, 10);
  EXPECT_THAT(loss.values,
              ElementsAre(DoubleNear(0.001, 1e-15), DoubleNear(0.01, 1e-15), DoubleNear(0.1, 1e-15),
                          DoubleNear(1, 1e-15), DoubleNear(10, 1e-15)));
  // A short range gets 2x and 5x ticks so it has more than two labels.
  EXPECT_THAT(LogTicks(0.2, 0.5).values, ElementsAre(DoubleNear(0.1, 1e-15), DoubleNear(0.2, 1e-15),
                                                     DoubleNear(0.5, 1e-15), DoubleNear(1, 1e-15)));
  // A huge range strides decades to keep at most ~8 labels.
  const AxisTicks wide = LogTicks(1e-12, 1e6);
  EXPECT_LE(wide.values.size(), 9u);
  EXPECT_LE(wide.lo, 1e-12);
  EXPECT_GE(wide.hi, 1e6);
  EXPECT_THROW(LogTicks(0, 1), std::invalid_argument);
  EXPECT_THROW(LogTicks(-1, 1), std::invalid_argument);
}

TEST(TicksTest, TickLabels) {
  EXPECT_EQ(FormatTick(15, 1), "15");
  EXPECT_EQ(FormatTick(2.5, 0.5), "2.5");
  EXPECT_EQ(FormatTick(0.1 * 3, 0.1), "0.3");
  EXPECT_EQ(FormatTick(0.0014, 0.0002), "0.0014");
  EXPECT_EQ(FormatTick(-1e-17, 0.5), "0.0");
  EXPECT_EQ(FormatTick(6000, 1000), "6000");
  EXPECT_EQ(FormatLogTick(0.001, true), "0.001");
  EXPECT_EQ(FormatLogTick(100, true), "100");
  EXPECT_EQ(FormatLogTick(0.2, true), "0.2");
  EXPECT_EQ(FormatLogTick(1e-5, false), "1e-5");
  EXPECT_EQ(FormatLogTick(2e-6, false), "2e-6");
  EXPECT_EQ(FormatLogTick(1e6, false), "1e6");
  EXPECT_EQ(FormatLogTick(1, false), "1e0");
  // One style per axis: a loss axis reaching 1e-5 labels every tick with exponents.
  EXPECT_TRUE(UsePlainLogLabels(LogTicks(0.0002, 8)));
  EXPECT_FALSE(UsePlainLogLabels(LogTicks(0.00002, 8)));
  EXPECT_FALSE(UsePlainLogLabels(LogTicks(1, 1e7)));
}

TEST(TicksTest, ValueLabels) {
  EXPECT_EQ(FormatValue(16.8237, 17.1), "16.82");
  EXPECT_EQ(FormatValue(10, 17.1), "10.00");
  EXPECT_EQ(FormatValue(123.45, 150), "123.5");
  EXPECT_EQ(FormatValue(1234.6, 1500), "1235");
  EXPECT_EQ(FormatValue(0.8333, 0.9), "0.83");
  EXPECT_EQ(FormatValue(0.0412, 0.05), "0.041");
}

}  // namespace
}  // namespace recon::report
