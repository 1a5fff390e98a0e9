// Static 2D, designed from the paper (docs/worlds.md).

#include <cmath>
#include <set>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/worlds/static2d.h"
#include "engine/worlds/world.h"

namespace recon::worlds {
namespace {

Static2D MakeS2(const std::string& placement, double sigma = 0.0) {
  Static2DOptions options;
  options.placement = placement;
  options.noise_sigma = sigma;
  return Static2D(options);
}

// The slot of the object lying between the other two, found from the geometry alone.
int MiddleSlot(const std::array<Vec2, 3>& objects) {
  for (int m = 0; m < 3; ++m) {
    const Vec2& a = objects[(m + 1) % 3];
    const Vec2& b = objects[(m + 2) % 3];
    if (std::abs(Distance(a, objects[m]) + Distance(objects[m], b) - Distance(a, b)) < 1e-9)
      return m;
  }
  return -1;
}

TEST(Static2D, Spec) {
  for (const auto& [placement, d] :
       std::vector<std::pair<std::string, int>>{{"none", 0}, {"position", 2}, {"distance", 1}}) {
    Static2D world = MakeS2(placement);
    EXPECT_EQ(world.Spec().b_dim, d);
    EXPECT_EQ(world.Spec().x_dim, 2);
    EXPECT_EQ(world.Spec().u_dim, 2);
    EXPECT_EQ(world.Spec().y_shape, (std::vector<int64_t>{6}));
    EXPECT_EQ(static_cast<int>(world.BeaconReading().size()), d);
  }
  Static2D world = MakeS2("position");
  EXPECT_EQ(world.EpisodeLength(), 10);
  EXPECT_FALSE(world.HigherIsBetter());
  EXPECT_EQ(world.PlaySamplesPerScenario(), 3);
}

TEST(Static2D, CentreIsTheGeometricMiddleOfThreeObjectsOnALine) {
  Static2D world = MakeS2("position");
  for (uint64_t seed = 0; seed < 1000; ++seed) {
    world.Reset(seed);
    const Static2DState& s = world.state();
    ASSERT_EQ(MiddleSlot(s.objects), s.centre) << "seed " << seed;
    const Vec2& c = s.objects[s.centre];
    const Vec2& a = s.objects[(s.centre + 1) % 3];
    const Vec2& b = s.objects[(s.centre + 2) % 3];
    EXPECT_NEAR(Distance(a, c), Distance(b, c), 1e-9);  // equally spaced
    EXPECT_GE(Distance(a, c), Static2D::kMinSpacing);
    EXPECT_LE(Distance(a, c), Static2D::kMaxSpacing);
    EXPECT_LE(std::abs(c[0]), Static2D::kTargetHalfWidth);
    EXPECT_LE(std::abs(c[1]), Static2D::kTargetHalfWidth);
    EXPECT_LE(std::abs(s.robot[0]), Static2D::kStartHalfWidth);
    EXPECT_LE(std::abs(s.robot[1]), Static2D::kStartHalfWidth);
    EXPECT_LE(Distance(s.robot, c), 10.0);  // reachable in 10 unit steps
    // y lists the objects in slot order.
    const std::vector<float> y = world.Observe().y;
    for (int k = 0; k < 3; ++k) {
      EXPECT_FLOAT_EQ(y[2 * k], static_cast<float>(s.objects[k][0]));
      EXPECT_FLOAT_EQ(y[2 * k + 1], static_cast<float>(s.objects[k][1]));
    }
  }
}

TEST(Static2D, ObjectsAreShuffledSoEverySlotHoldsTheCentreAboutATHird) {
  Static2D world = MakeS2("none");
  std::vector<int> count(3, 0);
  const int n = 3000;
  for (uint64_t seed = 0; seed < n; ++seed) {
    world.Reset(seed);
    ++count[MiddleSlot(world.state().objects)];
  }
  for (int c : count) EXPECT_NEAR(c, n / 3, 100);
}

TEST(Static2D, ExpertReachesTheCentreWithinTenUnitSteps) {
  Static2D world = MakeS2("position");
  for (uint64_t seed = 0; seed < 1000; ++seed) {
    world.Reset(seed);
    const Vec2 target = world.state().objects[MiddleSlot(world.state().objects)];
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      const std::vector<float> u = world.ExpertAction();
      const double len = std::hypot(u[0], u[1]);
      ASSERT_LE(len, 1.0 + 1e-6);
      // A full unit step unless the target is closer than one unit.
      ASSERT_NEAR(len, std::min(1.0, Distance(world.state().robot, target)), 1e-5);
      world.Step(u);
    }
    ASSERT_LT(world.EpisodeMetric(), 1e-3) << "seed " << seed;
    ASSERT_NEAR(world.EpisodeMetric(), Distance(world.state().robot, target), 1e-12);
  }
}

TEST(Static2D, StandingStillScoresTheStartingDistance) {
  Static2D world = MakeS2("none");
  world.Reset(3);
  const double start = Distance(world.state().robot, world.state().objects[world.state().centre]);
  for (int t = 0; t < 10; ++t) world.Step({0.0f, 0.0f});
  EXPECT_DOUBLE_EQ(world.EpisodeMetric(), start);
  EXPECT_GT(start, 0.0);
}

TEST(Static2D, BeaconsTrackTheCentreObject) {
  Static2D position = MakeS2("position");
  Static2D distance = MakeS2("distance");
  for (uint64_t seed = 0; seed < 100; ++seed) {
    position.Reset(seed);
    distance.Reset(seed);
    for (int t = 0; t < 10; ++t) {
      const Static2DState& s = position.state();
      const Vec2& c = s.objects[MiddleSlot(s.objects)];
      EXPECT_EQ(position.BeaconReading(),
                (std::vector<float>{static_cast<float>(c[0]), static_cast<float>(c[1])}));
      const std::vector<float> d = distance.BeaconReading();
      ASSERT_EQ(d.size(), 1u);
      EXPECT_NEAR(d[0], Distance(distance.state().robot, c), 1e-5);
      position.Step(position.ExpertAction());
      distance.Step(distance.ExpertAction());
    }
  }
}

TEST(Static2D, NoiseHasTheConfiguredSigmaAndZeroMean) {
  Static2D world = MakeS2("position", 1.5);
  double sum = 0, sum_sq = 0;
  int n = 0;
  for (uint64_t seed = 0; seed < 1000; ++seed) {
    world.Reset(seed);
    const Vec2& c = world.state().objects[world.state().centre];
    for (int k = 0; k < 10; ++k) {
      const std::vector<float> b = world.BeaconReading();
      for (int i = 0; i < 2; ++i) {
        const double e = b[i] - static_cast<float>(c[i]);
        sum += e;
        sum_sq += e * e;
        ++n;
      }
    }
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 4 * 1.5 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum_sq / n - mean * mean) / 1.5, 1.0, 0.015);
}

TEST(Static2D, PlayComesFromFreshRandomLayoutsWithoutChangingTheScenario) {
  Static2D world = MakeS2("distance");
  world.Reset(8);
  const Static2DState before = world.state();
  std::set<float> first_coordinates;
  double max_abs = 0.0;
  for (int i = 0; i < 500; ++i) {
    const PlaySample play = world.SamplePlay();
    ASSERT_EQ(play.x.size(), 2u);
    ASSERT_EQ(play.y.size(), 6u);
    ASSERT_EQ(play.b.size(), 1u);
    const std::array<Vec2, 3> objects = {Vec2{play.y[0], play.y[1]}, Vec2{play.y[2], play.y[3]},
                                         Vec2{play.y[4], play.y[5]}};
    // Float rounding of the positions: accept a looser collinearity.
    int middle = -1;
    for (int m = 0; m < 3; ++m) {
      const Vec2& a = objects[(m + 1) % 3];
      const Vec2& b = objects[(m + 2) % 3];
      if (std::abs(Distance(a, objects[m]) + Distance(objects[m], b) - Distance(a, b)) < 1e-4)
        middle = m;
    }
    ASSERT_GE(middle, 0);
    EXPECT_NEAR(play.b[0], Distance({play.x[0], play.x[1]}, objects[middle]), 1e-4);
    max_abs = std::max({max_abs, std::abs(double{play.x[0]}), std::abs(double{play.x[1]})});
    first_coordinates.insert(play.y[0]);
  }
  EXPECT_EQ(first_coordinates.size(), 500u);  // a fresh layout each time
  EXPECT_LE(max_abs, Static2D::kPlayRobotHalfWidth);
  EXPECT_GT(max_abs, Static2D::kStartHalfWidth);  // robots beyond the start square too
  EXPECT_EQ(world.state().robot, before.robot);
  EXPECT_EQ(world.state().objects, before.objects);
}

TEST(Static2D, SameSeedSameScenario) {
  Static2D a = MakeS2("position", 1.0), b = MakeS2("position", 1.0);
  a.Reset(17);
  b.Reset(3);
  b.Reset(17);
  EXPECT_EQ(a.state().objects, b.state().objects);
  EXPECT_EQ(a.state().robot, b.state().robot);
  EXPECT_EQ(a.BeaconReading(), b.BeaconReading());
  EXPECT_EQ(a.SamplePlay().y, b.SamplePlay().y);
  b.Reset(18);
  EXPECT_NE(a.state().objects, b.state().objects);
}

TEST(Static2D, UnknownPlacementThrowsNamingTheValidOnes) {
  try {
    MakeS2("exact");
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("'exact'"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("none, position, distance"));
  }
  EXPECT_THROW(MakeS2("position", -0.5), UserError);
}

}  // namespace
}  // namespace recon::worlds
