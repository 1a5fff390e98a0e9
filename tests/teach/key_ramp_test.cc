// Fine control at the keys: a tap moves a small step even between two control periods, a held
// key starts slow and speeds up to full speed, and letting go stops at once.

#include "engine/teach/key_ramp.h"

#include <gtest/gtest.h>

namespace recon::teach {
namespace {

TEST(KeyRamp, ATapBetweenTwoPeriodsMovesOneStep) {
  KeyRamp ramp;
  ramp.Set(2, -1, 10.00);
  ramp.Set(2, 0, 10.03);  // let go before the next period
  auto share = ramp.Period(10.05);
  EXPECT_FLOAT_EQ(share[2], -static_cast<float>(KeyRamp::kTapShare));
  EXPECT_FLOAT_EQ(share[0], 0.0f);
  // Used up: the next period stands still.
  share = ramp.Period(10.15);
  EXPECT_FLOAT_EQ(share[2], 0.0f);
}

TEST(KeyRamp, AHeldKeyStartsSlowAndReachesFullSpeed) {
  KeyRamp ramp;
  ramp.Set(0, 1, 0.0);
  const float first = ramp.Period(0.0)[0];  // the tap's step
  EXPECT_FLOAT_EQ(first, static_cast<float>(KeyRamp::kTapShare));
  float previous = 0;
  for (int period = 1; period < 10; ++period) {
    const double t = 0.1 * period * KeyRamp::kRampSeconds;
    const float share = ramp.Period(t)[0];
    EXPECT_GT(share, previous) << "at " << t << " s";
    EXPECT_LT(share, 1.0f) << "at " << t << " s";
    EXPECT_GE(share, static_cast<float>(KeyRamp::kFineShare));
    previous = share;
  }
  EXPECT_FLOAT_EQ(ramp.Period(KeyRamp::kRampSeconds + 0.5)[0], 1.0f);
  ramp.Set(0, 0, 2.0);
  EXPECT_FLOAT_EQ(ramp.Period(2.0)[0], 0.0f);
}

TEST(KeyRamp, ReversingRestartsTheRampAndClearForgetsEverything) {
  KeyRamp ramp;
  ramp.Set(3, 1, 0.0);
  ramp.Period(0.0);
  EXPECT_FLOAT_EQ(ramp.Period(2.0)[3], 1.0f);
  ramp.Set(3, -1, 2.0);
  EXPECT_FLOAT_EQ(ramp.Period(2.0)[3], -static_cast<float>(KeyRamp::kTapShare));
  EXPECT_LT(ramp.Period(2.1)[3], 0.0f);
  EXPECT_GT(ramp.Period(2.1)[3], -1.0f);
  ramp.Set(1, 1, 2.1);
  ramp.Clear();
  const auto share = ramp.Period(2.2);
  for (float s : share) EXPECT_FLOAT_EQ(s, 0.0f);
  ramp.Set(7, 1, 0.0);  // no such channel: ignored
}

}  // namespace
}  // namespace recon::teach
