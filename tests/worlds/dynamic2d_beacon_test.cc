// Dynamic 2D beacons, noise and play data.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/worlds/dynamic2d.h"
#include "engine/worlds/world.h"
#include "tests/worlds/reference_image.h"

namespace recon::worlds {
namespace {

using testing::ExpectedImage;

Dynamic2D MakeD2(const std::string& placement, bool compat = false, double sigma = 0.0) {
  Dynamic2DOptions options;
  options.placement = placement;
  options.authors_compat = compat;
  options.noise_sigma = sigma;
  return Dynamic2D(options);
}

std::vector<float> F(const Vec2& p) { return {static_cast<float>(p[0]), static_cast<float>(p[1])}; }

std::vector<float> Concat(std::vector<float> a, const std::vector<float>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

float Dist(const Vec2& a, const Vec2& b) {
  return static_cast<float>(std::hypot(a[0] - b[0], a[1] - b[1]));
}

// The first seed whose red object has index `red`.
uint64_t SeedWithRed(int red) {
  Dynamic2D world({});
  for (uint64_t seed = 0;; ++seed) {
    world.Reset(seed);
    if (world.state().red == red) return seed;
  }
}

// Runs 100 expert episodes and checks every reading against `expected(state)`.
template <typename Expected>
void ExpectTracks(Dynamic2D& world, Expected expected) {
  for (uint64_t seed = 0; seed < 100; ++seed) {
    world.Reset(seed);
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      ASSERT_EQ(world.BeaconReading(), expected(world.state(), world.random_object()))
          << world.options().placement << " seed " << seed << " step " << t;
      world.Step(world.ExpertAction());
    }
  }
}

TEST(Dynamic2DBeacon, EachPlacementTracksItsObjectThroughAnEpisode) {
  using S = Dynamic2DState;
  auto red = [](const S& s) { return F(s.objects[s.red]); };
  auto other = [](const S& s) { return F(s.objects[(s.red + 3) % 4]); };
  Dynamic2D exact = MakeD2("exact");
  ExpectTracks(exact, [&](const S& s, int) { return red(s); });
  Dynamic2D partial = MakeD2("partial");
  ExpectTracks(partial, [&](const S& s, int) { return std::vector<float>{red(s)[0]}; });
  Dynamic2D oth = MakeD2("other");
  ExpectTracks(oth, [&](const S& s, int) { return other(s); });
  Dynamic2D rnd = MakeD2("random");
  ExpectTracks(rnd, [&](const S& s, int r) { return F(s.objects[r]); });
  Dynamic2D eo = MakeD2("exact+other");
  ExpectTracks(eo, [&](const S& s, int) { return Concat(red(s), other(s)); });
  Dynamic2D er = MakeD2("exact+random");
  ExpectTracks(er, [&](const S& s, int r) { return Concat(red(s), F(s.objects[r])); });
  Dynamic2D dist = MakeD2("distance");
  ExpectTracks(
      dist, [&](const S& s, int) { return std::vector<float>{Dist(s.robot, s.objects[s.red])}; });
  Dynamic2D none = MakeD2("none");
  ExpectTracks(none, [&](const S&, int) { return std::vector<float>{}; });
}

TEST(Dynamic2DBeacon, OtherNeverReadsTheRobotByDefault) {
  Dynamic2D world = MakeD2("other");
  world.Reset(SeedWithRed(0));
  for (int t = 0; t < world.EpisodeLength(); ++t) {
    const Dynamic2DState& s = world.state();
    EXPECT_EQ(world.BeaconReading(), F(s.objects[3]));  // (0 - 1) mod 4
    world.Step(world.ExpertAction());
    EXPECT_NE(world.BeaconReading(), F(world.state().robot));
  }
}

TEST(Dynamic2DBeacon, CompatOtherReadsTheRobotWhenRedIsObjectZero) {
  for (const std::string placement : {"other", "exact+other"}) {
    Dynamic2D world = MakeD2(placement, /*compat=*/true);
    world.Reset(SeedWithRed(0));
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      const Dynamic2DState& s = world.state();
      std::vector<float> b = world.BeaconReading();
      b.erase(b.begin(), b.end() - 2);  // the Other part
      EXPECT_EQ(b, F(s.robot)) << placement << " step " << t;
      world.Step(world.ExpertAction());
    }
  }
  // For any other red index the slip does not show.
  for (int red = 1; red < 4; ++red) {
    Dynamic2D world = MakeD2("other", /*compat=*/true);
    world.Reset(SeedWithRed(red));
    world.Step(world.ExpertAction());
    EXPECT_EQ(world.BeaconReading(), F(world.state().objects[red - 1]));
  }
}

TEST(Dynamic2DBeacon, RandomIsNeverRedConstantPerEpisodeAndSpreadOverTheOthers) {
  Dynamic2D world = MakeD2("random");
  std::vector<int> offset_count(4, 0);
  for (uint64_t seed = 0; seed < 600; ++seed) {
    world.Reset(seed);
    const int r = world.random_object();
    ASSERT_NE(r, world.state().red);
    ++offset_count[(r - world.state().red + 4) % 4];
    for (int t = 0; t < world.EpisodeLength(); ++t) {
      ASSERT_EQ(world.random_object(), r);
      ASSERT_EQ(world.BeaconReading(), F(world.state().objects[r]));
      world.Step(world.ExpertAction());
    }
  }
  EXPECT_EQ(offset_count[0], 0);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(offset_count[k], 200, 50);
}

TEST(Dynamic2DBeacon, NoiseHasTheConfiguredSigmaAndZeroMean) {
  for (double sigma : {2.5, 6.5}) {
    Dynamic2D world = MakeD2("exact", false, sigma);
    double sum = 0, sum_sq = 0;
    int n = 0;
    for (uint64_t seed = 0; seed < 200; ++seed) {
      world.Reset(seed);
      for (int t = 0; t < world.EpisodeLength(); ++t) {
        const std::vector<float> clean = F(world.state().objects[world.state().red]);
        for (int k = 0; k < 10; ++k) {
          const std::vector<float> b = world.BeaconReading();
          for (int i = 0; i < 2; ++i) {
            const double e = b[i] - clean[i];
            sum += e;
            sum_sq += e * e;
            ++n;
          }
        }
        world.Step(world.ExpertAction());
      }
    }
    const double mean = sum / n;
    const double sd = std::sqrt(sum_sq / n - mean * mean);
    EXPECT_NEAR(mean, 0.0, 4 * sigma / std::sqrt(n)) << sigma;
    EXPECT_NEAR(sd / sigma, 1.0, 0.015) << sigma;
  }
}

TEST(Dynamic2DBeacon, DrawingPlayDoesNotChangeTheDemonstration) {
  Dynamic2D world = MakeD2("exact", false, 2.5);
  const std::vector<uint64_t> seeds = {3, 4, 5};
  const Dataset without = RecordDemonstrations(world, seeds, 0);
  const Dataset with = RecordDemonstrations(world, seeds, 3);
  ASSERT_EQ(with.play.size(), 9u);
  for (size_t d = 0; d < seeds.size(); ++d) {
    for (size_t t = 0; t < without.demos[d].samples.size(); ++t) {
      EXPECT_EQ(without.demos[d].samples[t].b, with.demos[d].samples[t].b);
      EXPECT_EQ(without.demos[d].samples[t].y, with.demos[d].samples[t].y);
    }
  }
}

TEST(Dynamic2DBeacon, PlayDisplacesTheRobotUpToTenInEveryDirection) {
  Dynamic2D world = MakeD2("distance");
  world.Reset(12);
  world.Step(world.ExpertAction());
  const Dynamic2DState before = world.state();
  double sum_r = 0, sum_cos = 0, sum_sin = 0, max_r = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const PlaySample play = world.SamplePlay();
    const Vec2 x = {play.x[0], play.x[1]};
    const double dx = x[0] - before.robot[0], dy = x[1] - before.robot[1];
    const double r = std::hypot(dx, dy);
    ASSERT_LE(r, 10.0 + 1e-5);
    sum_r += r;
    max_r = std::max(max_r, r);
    sum_cos += dx / r;
    sum_sin += dy / r;
    ASSERT_NEAR(play.b[0], Dist(x, before.objects[before.red]), 1e-4);
  }
  EXPECT_NEAR(sum_r / n, 5.0, 0.2);  // 10 U(0, 1)
  EXPECT_GT(max_r, 9.9);
  EXPECT_NEAR(sum_cos / n, 0.0, 0.05);
  EXPECT_NEAR(sum_sin / n, 0.0, 0.05);
  // Drawing play leaves the scenario as it was.
  EXPECT_EQ(world.state().robot, before.robot);
  EXPECT_EQ(world.state().objects, before.objects);
}

TEST(Dynamic2DBeacon, PlayImagesShowTheDisplacedRobot) {
  for (bool compat : {false, true}) {
    Dynamic2D world = MakeD2("exact", compat);
    int differing = 0;
    for (uint64_t seed = 0; seed < 20; ++seed) {
      world.Reset(seed);
      for (int k = 0; k < 3; ++k) {
        const PlaySample play = world.SamplePlay();
        Dynamic2DState displaced = world.state();
        displaced.robot = {play.x[0], play.x[1]};
        const std::vector<float> shown = ExpectedImage(displaced, world.background());
        const std::vector<float> undisplaced = ExpectedImage(world.state(), world.background());
        EXPECT_EQ(play.y, compat ? undisplaced : shown) << "compat " << compat;
        differing += shown != undisplaced;
        EXPECT_EQ(play.b, F(world.state().objects[world.state().red]));
      }
    }
    EXPECT_GT(differing, 50);  // the displacement almost always moves the robot's pixels
  }
}

TEST(Dynamic2DBeacon, PlayNoiseUsesTheConfiguredSigma) {
  Dynamic2D world = MakeD2("partial", false, 4.5);
  world.Reset(0);
  const double clean = world.state().objects[world.state().red][0];
  double sum_sq = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double e = world.SamplePlay().b[0] - clean;
    sum_sq += e * e;
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n) / 4.5, 1.0, 0.015);
}

}  // namespace
}  // namespace recon::worlds
