// The safety envelope's rules on exact numbers: each rule alone, then together.

#include "engine/safety/safety_envelope.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/safety/ur5_kinematics.h"
#include "tests/safety/garbage_commands.h"

namespace recon::safety {
namespace {

using ::testing::HasSubstr;

// The simulated cell's home: the tool about 0.3 m above the table, pointing down.
constexpr JointVector kHome = {3.14159265358979, -1.9, 1.9, -1.5708, -1.5708, 0.0};
constexpr double kPeriod = 0.1;

TEST(SafetyEnvelopeTest, PassesACommandInsideTheLimitsUnchanged) {
  SafetyEnvelope envelope{SafetyLimits{}};
  const JointVector v = {0.2, -0.1, 0.05, 0.0, 0.1, -0.2};
  const SafetyDecision d = envelope.Filter(kHome, v, v, kPeriod);
  EXPECT_EQ(d.reasons, kNone) << DescribeReasons(d.reasons);
  EXPECT_EQ(d.command_rad_s, v);
  EXPECT_GT(d.tool_z_m, 0.1);
}

TEST(SafetyEnvelopeTest, NonFiniteCommandsAndStatesAreStops) {
  SafetyEnvelope envelope{SafetyLimits{}};
  const JointVector moving = {0.2, 0, 0, 0, 0, 0};
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    JointVector v = moving;
    v[3] = bad;
    const SafetyDecision d = envelope.Filter(kHome, moving, v, kPeriod);
    EXPECT_EQ(d.reasons, kNonFinite);
    EXPECT_EQ(d.command_rad_s, JointVector{});
    JointVector q = kHome;
    q[1] = bad;
    EXPECT_EQ(envelope.Filter(q, moving, moving, kPeriod).command_rad_s, JointVector{});
  }
}

TEST(SafetyEnvelopeTest, ScalesTheVelocityKeepingItsDirection) {
  SafetyLimits limits;
  limits.max_acceleration_rad_s2.fill(1e6);  // this test is about velocity alone
  SafetyEnvelope envelope{limits};
  const JointVector v = {4.0, -2.0, 0, 0, 1.0, 0};
  const SafetyDecision d = envelope.Filter(kHome, v, v, kPeriod);
  EXPECT_TRUE(d.reasons & kVelocity);
  EXPECT_NEAR(d.command_rad_s[0], 1.0, 1e-12);  // the fastest joint meets its limit
  EXPECT_NEAR(d.command_rad_s[1], -0.5, 1e-12);
  EXPECT_NEAR(d.command_rad_s[4], 0.25, 1e-12);
  // A huge command is as safe as a merely fast one.
  const JointVector huge = {1e300, -1e300, 0, 0, 0, 0};
  const SafetyDecision h = envelope.Filter(kHome, huge, huge, kPeriod);
  EXPECT_NEAR(h.command_rad_s[0], 1.0, 1e-12);
  EXPECT_NEAR(h.command_rad_s[1], -1.0, 1e-12);
}

TEST(SafetyEnvelopeTest, LimitsSpeedingUpButNeverBraking) {
  SafetyEnvelope envelope{SafetyLimits{}};  // 5 rad/s^2: 0.5 rad/s per 0.1 s
  const JointVector rest{};
  const JointVector fast = {0.9, 0, 0, 0, -0.9, 0};
  const SafetyDecision up = envelope.Filter(kHome, rest, fast, kPeriod);
  EXPECT_TRUE(up.reasons & kAcceleration);
  EXPECT_NEAR(up.command_rad_s[0], 0.5, 1e-12);
  EXPECT_NEAR(up.command_rad_s[4], -0.5, 1e-12);
  // Half the period, half the change.
  EXPECT_NEAR(envelope.Filter(kHome, rest, fast, kPeriod / 2).command_rad_s[0], 0.25, 1e-12);
  // From full speed to a stop in one step is allowed: stopping must always be possible.
  const SafetyDecision stop = envelope.Filter(kHome, fast, rest, kPeriod);
  EXPECT_EQ(stop.reasons, kNone);
  EXPECT_EQ(stop.command_rad_s, rest);
  // Reversing is speeding up in the other direction.
  const JointVector reverse = {-0.9, 0, 0, 0, 0.9, 0};
  const SafetyDecision r = envelope.Filter(kHome, fast, reverse, kPeriod);
  EXPECT_TRUE(r.reasons & kAcceleration);
  EXPECT_NEAR(r.command_rad_s[0], 0.4, 1e-12);
}

TEST(SafetyEnvelopeTest, StopsAJointAtItsPositionLimit) {
  SafetyLimits limits;
  limits.max_position_rad[5] = 0.5;
  SafetyEnvelope envelope{limits};
  JointVector q = kHome;
  q[5] = 0.47;
  const JointVector v = {0, 0, 0, 0, 0, 0.5};
  const SafetyDecision d = envelope.Filter(q, v, v, kPeriod);
  EXPECT_TRUE(d.reasons & kPositionLimit);
  EXPECT_NEAR(d.command_rad_s[5], 0.3, 1e-9);  // reaches 0.5 exactly within the lookahead
  q[5] = 0.6;                                  // already past: it may only come back
  EXPECT_EQ(envelope.Filter(q, v, v, kPeriod).command_rad_s[5], 0.0);
  const JointVector back = {0, 0, 0, 0, 0, -0.5};
  EXPECT_EQ(envelope.Filter(q, back, back, kPeriod).command_rad_s[5], -0.5);
}

/// Joint velocities that move the tool straight down at about `speed` m/s (a finite-difference
/// Jacobian solved by least squares).
JointVector DownwardVelocity(const JointVector& q, double speed) {
  Eigen::Matrix<double, 3, 6> jacobian;
  const Eigen::Vector3d p = Ur5ToolPoint(q, 0.1);
  for (int i = 0; i < 6; ++i) {
    JointVector dq = q;
    dq[i] += 1e-6;
    jacobian.col(i) = (Ur5ToolPoint(dq, 0.1) - p) / 1e-6;
  }
  const Eigen::Matrix<double, 6, 1> v =
      jacobian.completeOrthogonalDecomposition().solve(Eigen::Vector3d(0, 0, -speed));
  JointVector out;
  for (int i = 0; i < 6; ++i) out[i] = v[i];
  return out;
}

TEST(SafetyEnvelopeTest, KeepsTheToolAboveTheFloor) {
  SafetyEnvelope envelope{SafetyLimits{}};
  const double home_z = envelope.ToolPoint(kHome).z();
  ASSERT_GT(home_z, 0.2);
  // Lowering the floor to just under the tool: a descent is scaled to end on the floor.
  SafetyLimits limits;
  limits.tool_floor_m = home_z - 0.01;
  SafetyEnvelope near_floor{limits};
  const JointVector down = DownwardVelocity(kHome, 0.3);  // 3 cm in the lookahead
  const SafetyDecision d = near_floor.Filter(kHome, down, down, kPeriod);
  EXPECT_TRUE(d.reasons & kToolFloor);
  JointVector q_next;
  for (int i = 0; i < 6; ++i) q_next[i] = kHome[i] + d.command_rad_s[i] * limits.lookahead_s;
  EXPECT_NEAR(near_floor.ToolPoint(q_next).z(), limits.tool_floor_m, 1e-6);
  // Moving up is always allowed, even from below the floor.
  limits.tool_floor_m = home_z + 0.05;
  SafetyEnvelope above{limits};
  const JointVector up = DownwardVelocity(kHome, -0.1);
  EXPECT_EQ(above.Filter(kHome, up, up, kPeriod).reasons, kNone);
  EXPECT_EQ(above.Filter(kHome, down, down, kPeriod).command_rad_s, JointVector{});
}

TEST(SafetyEnvelopeTest, RandomGarbageNeverLeavesTheEnvelope) {
  const SafetyLimits limits;
  SafetyEnvelope envelope{limits};
  Rng rng(2026);  // seed 2026: 20000 commands of garbage, integrated from home
  JointVector q = kHome, previous{};
  for (int step = 0; step < 20000; ++step) {
    const JointVector v = testing::GarbageJointVelocities(rng, {0.05, 0.3, 1e6, 3});
    const SafetyDecision d = envelope.Filter(q, previous, v, kPeriod);
    for (int i = 0; i < 6; ++i) {
      const double out = d.command_rad_s[i];
      ASSERT_TRUE(std::isfinite(out));
      ASSERT_LE(std::abs(out), limits.max_velocity_rad_s[i] + 1e-9) << "step " << step;
      const bool braking = out * previous[i] >= 0 && std::abs(out) <= std::abs(previous[i]);
      if (!braking) {
        ASSERT_LE(std::abs(out - previous[i]), limits.max_acceleration_rad_s2[i] * kPeriod + 1e-9);
      }
      q[i] += out * kPeriod;
      ASSERT_GE(q[i], limits.min_position_rad[i] - 1e-9);
      ASSERT_LE(q[i], limits.max_position_rad[i] + 1e-9);
    }
    // The floor holds up to the curvature of one lookahead step (sub-millimetre).
    ASSERT_GE(envelope.ToolPoint(q).z(), limits.tool_floor_m - 1e-3) << "step " << step;
    previous = d.command_rad_s;
  }
}

TEST(SafetyEnvelopeTest, InvalidLimitsNameTheField) {
  SafetyLimits limits;
  limits.max_velocity_rad_s[2] = -1;
  EXPECT_THAT([&] { SafetyEnvelope{limits}; },
              ::testing::ThrowsMessage<UserError>(HasSubstr("max_velocity_rad_s[2]")));
  limits = SafetyLimits{};
  limits.min_position_rad[4] = 3;
  limits.max_position_rad[4] = 2;
  EXPECT_THAT([&] { SafetyEnvelope{limits}; },
              ::testing::ThrowsMessage<UserError>(HasSubstr("joint 4")));
  limits = SafetyLimits{};
  limits.watchdog_timeout_s = std::nan("");
  EXPECT_THAT([&] { SafetyEnvelope{limits}; },
              ::testing::ThrowsMessage<UserError>(HasSubstr("watchdog_timeout_s")));
}

TEST(SafetyEnvelopeTest, DescribesReasons) {
  EXPECT_EQ(DescribeReasons(kNone), "none");
  EXPECT_EQ(DescribeReasons(kVelocity | kToolFloor), "velocity, tool floor");
}

}  // namespace
}  // namespace recon::safety
