// Homing before a trial: a joint-space move that arrives, every joint together, without
// overshooting, and refuses what a person should do by hand.

#include "engine/teach/homing.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::teach {
namespace {

using ::testing::HasSubstr;
using Joints = std::array<double, 6>;

constexpr Joints kHome{0.0, -1.57, 1.57, -1.57, -1.57, 0.0};

TEST(HomingTest, ArrivesFromAnywhereNearWithEveryJointTogetherAndNoOvershoot) {
  Rng rng(12);  // seed 12: 20 start poses within 1.5 rad of home in every joint
  const HomingLimits limits;
  for (int pose = 0; pose < 20; ++pose) {
    Joints q = kHome;
    for (double& x : q) x += rng.Uniform(-1.5, 1.5);
    const Joints start = q;
    int periods = 0;
    while (const std::optional<Joints> v = HomingVelocity(q, kHome, limits)) {
      double fastest = 0;
      // Every joint heads home in proportion to what it has left: one ratio for all.
      const double ratio = (*v)[0] / (kHome[0] - q[0]);
      EXPECT_GT(ratio, 0);
      for (int i = 0; i < 6; ++i) {
        fastest = std::max(fastest, std::abs((*v)[i]));
        EXPECT_NEAR((*v)[i], ratio * (kHome[i] - q[i]), 1e-9) << "joint " << i;
      }
      EXPECT_LE(fastest, limits.max_speed_rad_s + 1e-12);
      for (int i = 0; i < 6; ++i) q[i] += (*v)[i] * 0.1;  // an ideal arm, one 0.1 s period
      // Never past home: what is left keeps its sign.
      for (int i = 0; i < 6; ++i) EXPECT_GE((kHome[i] - q[i]) * (kHome[i] - start[i]), 0);
      ASSERT_LT(++periods, 200) << "pose " << pose << " never arrived";
    }
    EXPECT_LE(HomingDistance(q, kHome), limits.tolerance_rad);
    // The cap sets the pace: the farthest joint cannot arrive sooner than distance / cap.
    EXPECT_GE(periods * 0.1, HomingDistance(start, kHome) / limits.max_speed_rad_s - 1e-9);
  }
}

TEST(HomingTest, AnArmAtHomeStaysAndOneTooFarOrLostIsRefusedNamingTheJoint) {
  EXPECT_FALSE(HomingVelocity(kHome, kHome).has_value());
  Joints near = kHome;
  near[3] += 0.004;
  EXPECT_FALSE(HomingVelocity(near, kHome).has_value());
  Joints far = kHome;
  far[4] += 4.0;
  EXPECT_THAT([&] { HomingVelocity(far, kHome); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("joint 5 is 4.00 rad")));
  Joints lost = kHome;
  lost[0] = std::nan("");
  EXPECT_THAT([&] { HomingVelocity(lost, kHome); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("joint 1")));
  EXPECT_TRUE(std::isinf(HomingDistance(lost, kHome)));
  HomingLimits bad;
  bad.gain_per_s = 0;
  EXPECT_THAT([&] { HomingVelocity(near, kHome, bad); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("gain_per_s")));
}

}  // namespace
}  // namespace recon::teach
