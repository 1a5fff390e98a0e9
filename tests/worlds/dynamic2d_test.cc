// Dynamic 2D scenarios, dynamics, expert and score against REFERENCE.md section 2.

#include <cmath>
#include <set>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/worlds/dynamic2d.h"

namespace recon::worlds {
namespace {

double Angle(const Vec2& p) { return std::atan2(p[1], p[0]); }

// Difference of two angles wrapped into [-pi, pi).
double AngleDiff(double a, double b) {
  double d = std::fmod(a - b + 3 * M_PI, 2 * M_PI);
  if (d < 0) d += 2 * M_PI;
  return d - M_PI;
}

TEST(Dynamic2D, SpecFollowsThePlacement) {
  const std::vector<std::pair<std::string, int>> dims = {
      {"none", 0},   {"exact", 2},       {"partial", 1},      {"other", 2},
      {"random", 2}, {"exact+other", 4}, {"exact+random", 4}, {"distance", 1}};
  for (const auto& [placement, d] : dims) {
    Dynamic2DOptions options;
    options.placement = placement;
    Dynamic2D world(options);
    const DataSpec spec = world.Spec();
    EXPECT_EQ(spec.b_dim, d) << placement;
    EXPECT_EQ(spec.x_dim, 2);
    EXPECT_EQ(spec.u_dim, 2);
    EXPECT_EQ(spec.y_shape, (std::vector<int64_t>{3, 32, 32}));
    EXPECT_EQ(static_cast<int>(world.BeaconReading().size()), d) << placement;
  }
  EXPECT_EQ(Dynamic2D(Dynamic2DOptions{}).EpisodeLength(), 10);
  EXPECT_EQ(Dynamic2D(Dynamic2DOptions{}).PlaySamplesPerScenario(), 3);
  EXPECT_TRUE(Dynamic2D(Dynamic2DOptions{}).HigherIsBetter());
}

TEST(Dynamic2D, ScenarioLayoutAndColours) {
  std::vector<int> red_count(4, 0);
  double min_t = 10, max_t = -10;
  for (uint64_t seed = 0; seed < 400; ++seed) {
    Dynamic2D world({});
    world.Reset(seed);
    const Dynamic2DState& s = world.state();
    EXPECT_EQ(s.robot, (Vec2{0.0, 0.0}));
    const double t = Angle(s.objects[0]);
    min_t = std::min(min_t, t);
    max_t = std::max(max_t, t);
    const double offsets[4] = {0, M_PI / 2, M_PI, -M_PI / 2};
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(std::hypot(s.objects[i][0], s.objects[i][1]), 10.0, 1e-9);
      EXPECT_NEAR(AngleDiff(Angle(s.objects[i]), t + offsets[i]), 0.0, 1e-9);
    }
    // Colours: two olive (5), one green (0), and red (10) two places before the green one.
    int green = -1, olive = 0;
    for (int i = 0; i < 4; ++i) {
      if (s.colours[i] == 0.0) green = i;
      if (s.colours[i] == 5.0) ++olive;
    }
    ASSERT_GE(green, 0);
    EXPECT_EQ(olive, 2);
    EXPECT_EQ(s.red, (green + 2) % 4);
    EXPECT_EQ(s.colours[s.red], 10.0);
    ++red_count[s.red];
  }
  EXPECT_LT(min_t, -3.0);  // t covers [-pi, pi)
  EXPECT_GT(max_t, 3.0);
  for (int n : red_count) EXPECT_NEAR(n, 100, 35);
}

TEST(Dynamic2D, StepMovesRobotByUAndRotatesObjectsAnticlockwise) {
  Dynamic2D world({});
  world.Reset(5);
  const Dynamic2DState before = world.state();
  world.Step({3.5f, -20.0f});  // no clipping
  const Dynamic2DState& after = world.state();
  EXPECT_DOUBLE_EQ(after.robot[0], 3.5);
  EXPECT_DOUBLE_EQ(after.robot[1], -20.0);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(AngleDiff(Angle(after.objects[i]), Angle(before.objects[i])), M_PI / 24, 1e-12);
    EXPECT_NEAR(std::hypot(after.objects[i][0], after.objects[i][1]), 10.0, 1e-9);
  }
  EXPECT_EQ(after.colours, before.colours);
  EXPECT_EQ(after.red, before.red);
  EXPECT_THROW(world.Step({1.0f}), std::invalid_argument);
}

TEST(Dynamic2D, ExpertStepsAwayFromRedAndScores17785InEveryScenario) {
  Dynamic2D world({});
  for (uint64_t seed = 0; seed < 300; ++seed) {
    world.Reset(seed);
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      const Dynamic2DState& s = world.state();
      const Vec2& red = s.objects[s.red];
      const std::vector<float> u = world.ExpertAction();
      const double away[2] = {s.robot[0] - red[0], s.robot[1] - red[1]};
      const double n = std::hypot(away[0], away[1]);
      ASSERT_NEAR(u[0], away[0] / n, 1e-6);
      ASSERT_NEAR(u[1], away[1] / n, 1e-6);
      world.Step(u);
    }
    ASSERT_NEAR(world.EpisodeMetric(), 17.785, 1e-3) << "seed " << seed;
  }
}

TEST(Dynamic2D, ScoreIsTakenAfterTheNinthMoveBeforeTheObjectsRotate) {
  Dynamic2D world({});
  world.Reset(21);
  for (int t = 0; t < 8; ++t) {
    world.Step(world.ExpertAction());
    const Dynamic2DState& s = world.state();
    // Before the scored step the metric is the current distance.
    EXPECT_DOUBLE_EQ(world.EpisodeMetric(), std::hypot(s.robot[0] - s.objects[s.red][0],
                                                       s.robot[1] - s.objects[s.red][1]));
  }
  const Dynamic2DState s = world.state();
  const std::vector<float> u = world.ExpertAction();
  const double expected =
      std::hypot(s.robot[0] + u[0] - s.objects[s.red][0], s.robot[1] + u[1] - s.objects[s.red][1]);
  world.Step(u);
  EXPECT_NEAR(world.EpisodeMetric(), expected, 1e-12);
  EXPECT_NEAR(expected, 17.785, 1e-3);
  world.Step({100.0f, 100.0f});  // the 10th action is executed but not scored
  EXPECT_NEAR(world.EpisodeMetric(), expected, 1e-12);
  EXPECT_EQ(world.steps(), 10);
  world.Reset(21);
  EXPECT_EQ(world.steps(), 0);
  EXPECT_DOUBLE_EQ(world.EpisodeMetric(), 10.0);
}

TEST(Dynamic2D, StandingStillScoresTen) {
  Dynamic2D world({});
  for (uint64_t seed = 0; seed < 200; ++seed) {
    world.Reset(seed);
    for (int t = 0; t < world.EpisodeLength(); ++t) world.Step({0.0f, 0.0f});
    ASSERT_NEAR(world.EpisodeMetric(), 10.0, 1e-9);
  }
}

TEST(Dynamic2D, ExpertStopsOnceOnTheCircle) {
  Dynamic2D world({});
  world.Reset(1);
  world.Step({10.0f, 0.0f});
  EXPECT_EQ(world.ExpertAction(), (std::vector<float>{0.0f, 0.0f}));
}

TEST(Dynamic2D, SameSeedSameScenarioDifferentSeedsDiffer) {
  Dynamic2DOptions options;
  options.placement = "exact+random";
  options.noise_sigma = 1.0;
  Dynamic2D a(options), b(options);
  a.Reset(42);
  b.Reset(7);
  b.Reset(42);  // a Reset fully replaces the previous scenario, noise stream included
  EXPECT_EQ(a.state().objects, b.state().objects);
  EXPECT_EQ(a.state().colours, b.state().colours);
  EXPECT_EQ(a.background(), b.background());
  for (int t = 0; t < 10; ++t) {
    EXPECT_EQ(a.BeaconReading(), b.BeaconReading());
    EXPECT_EQ(a.Observe().y, b.Observe().y);
    const PlaySample pa = a.SamplePlay(), pb = b.SamplePlay();
    EXPECT_EQ(pa.x, pb.x);
    EXPECT_EQ(pa.b, pb.b);
    a.Step(a.ExpertAction());
    b.Step(b.ExpertAction());
  }
  std::set<double> angles;
  for (uint64_t seed = 0; seed < 50; ++seed) {
    a.Reset(seed);
    angles.insert(Angle(a.state().objects[0]));
  }
  EXPECT_EQ(angles.size(), 50u);
  a.Reset(1);
  b.Reset(2);
  EXPECT_NE(a.background(), b.background());
}

TEST(Dynamic2D, LayoutDoesNotDependOnPlacementNoiseOrObservation) {
  Dynamic2DOptions other;
  other.placement = "random";
  other.noise_sigma = 3.0;
  other.observation = "state";
  Dynamic2D a({}), b(other);
  a.Reset(99);
  b.Reset(99);
  EXPECT_EQ(a.state().objects, b.state().objects);
  EXPECT_EQ(a.state().red, b.state().red);
  EXPECT_EQ(a.background(), b.background());
}

TEST(Dynamic2D, BadOptionsThrowUserErrorNamingTheValidOnes) {
  Dynamic2DOptions options;
  options.placement = "exactly";
  try {
    Dynamic2D world(options);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    const std::string msg = e.what();
    EXPECT_THAT(msg, ::testing::HasSubstr("exactly"));
    for (const char* name : {"none", "exact", "partial", "other", "random", "exact+other",
                             "exact+random", "distance"}) {
      EXPECT_THAT(msg, ::testing::HasSubstr(name));
    }
  }
  EXPECT_THROW(MakeDynamic2D(options), UserError);
  options.placement = "exact";
  options.noise_sigma = -1.0;
  EXPECT_THROW(MakeDynamic2D(options), UserError);
  options.noise_sigma = NAN;
  EXPECT_THROW(MakeDynamic2D(options), UserError);
  options.noise_sigma = 0.0;
  options.observation = "pixels";
  EXPECT_THROW(MakeDynamic2D(options), UserError);
}

}  // namespace
}  // namespace recon::worlds
