// RecordDemonstrations, Rollout and the world factory.

#include <cmath>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/dataset.h"
#include "engine/core/error.h"
#include "engine/worlds/dynamic2d.h"
#include "engine/worlds/static2d.h"
#include "engine/worlds/world.h"
#include "engine/worlds/world_factory.h"

namespace recon::worlds {
namespace {

using ::testing::HasSubstr;

TEST(RecordDemonstrations, ShapesAndCounts) {
  for (const auto& [name, placement, y_size, b_dim] :
       std::vector<std::tuple<std::string, std::string, size_t, size_t>>{
           {"dynamic2d", "exact+other", 3072, 4},
           {"dynamic2d-state", "distance", 14, 1},
           {"static2d", "position", 6, 2},
           {"static2d", "none", 6, 0}}) {
    auto world = MakeWorld(name, placement, 0.0, false);
    const Dataset data = RecordDemonstrations(*world, {1, 2, 3, 4, 5}, 3);
    EXPECT_EQ(data.spec, world->Spec());
    ASSERT_EQ(data.demos.size(), 5u);
    EXPECT_EQ(data.play.size(), 15u);
    EXPECT_EQ(data.NumDemoSamples(), 50);
    for (const Episode& e : data.demos) {
      ASSERT_EQ(e.samples.size(), 10u);
      for (const Sample& s : e.samples) {
        EXPECT_EQ(s.x.size(), 2u);
        EXPECT_EQ(s.y.size(), y_size);
        EXPECT_EQ(s.b.size(), b_dim);
        EXPECT_EQ(s.u.size(), 2u);
      }
    }
    for (const PlaySample& p : data.play) {
      EXPECT_EQ(p.x.size(), 2u);
      EXPECT_EQ(p.y.size(), y_size);
      EXPECT_EQ(p.b.size(), b_dim);
    }
    EXPECT_NO_THROW(ValidateDataset(data));
  }
}

TEST(RecordDemonstrations, RecordsTheExpertsActionsAndTheStateBeforeEachStep) {
  Dynamic2D world({});
  const std::vector<uint64_t> seeds = {10, 11, 12};
  const Dataset data = RecordDemonstrations(world, seeds, 3);
  Dynamic2D replay({});
  for (size_t d = 0; d < seeds.size(); ++d) {
    replay.Reset(seeds[d]);
    const std::vector<Sample>& samples = data.demos[d].samples;
    for (const Sample& s : samples) {
      const Dynamic2DState& st = replay.state();
      // An expert step: a unit vector pointing away from red, recorded with x before the step.
      EXPECT_NEAR(std::hypot(s.u[0], s.u[1]), 1.0, 1e-6);
      EXPECT_EQ(s.x, (std::vector<float>{static_cast<float>(st.robot[0]),
                                         static_cast<float>(st.robot[1])}));
      EXPECT_EQ(s.b, (std::vector<float>{static_cast<float>(st.objects[st.red][0]),
                                         static_cast<float>(st.objects[st.red][1])}));
      EXPECT_EQ(s.y, replay.Observe().y);
      EXPECT_EQ(s.u, replay.ExpertAction());
      replay.Step(s.u);
    }
    EXPECT_NEAR(replay.EpisodeMetric(), 17.785, 1e-3);
    // Consecutive samples follow the action.
    for (size_t t = 1; t < samples.size(); ++t) {
      EXPECT_NEAR(samples[t].x[0], samples[t - 1].x[0] + samples[t - 1].u[0], 1e-5);
      EXPECT_NEAR(samples[t].x[1], samples[t - 1].x[1] + samples[t - 1].u[1], 1e-5);
    }
  }
}

TEST(RecordDemonstrations, PlayCountIsTheArgumentAndNegativeIsAUserError) {
  Static2D world({});
  EXPECT_TRUE(RecordDemonstrations(world, {1, 2}, 0).play.empty());
  EXPECT_EQ(RecordDemonstrations(world, {1, 2}, 7).play.size(), 14u);
  EXPECT_THROW(RecordDemonstrations(world, {1}, -1), UserError);
}

TEST(Rollout, ExpertAndStandStillScoresInBothWorlds) {
  auto dynamic = MakeWorld("dynamic2d", "none", 0.0, false);
  auto stat = MakeWorld("static2d", "none", 0.0, false);
  for (uint64_t seed = 100; seed < 120; ++seed) {
    EXPECT_NEAR(
        Rollout(*dynamic, seed, [&](const Observation&) { return dynamic->ExpertAction(); }),
        17.785, 1e-3);
    EXPECT_NEAR(Rollout(*dynamic, seed,
                        [](const Observation&) {
                          return std::vector<float>{0.0f, 0.0f};
                        }),
                10.0, 1e-9);
    EXPECT_LT(Rollout(*stat, seed, [&](const Observation&) { return stat->ExpertAction(); }), 1e-3);
  }
}

TEST(Rollout, PolicySeesTheObservationOfEachStep) {
  Static2D world({});
  world.Reset(4);
  const Static2DState start = world.state();
  const double initial =
      std::hypot(start.robot[0] - start.objects[0][0], start.robot[1] - start.objects[0][1]);
  std::vector<std::vector<float>> seen;
  // A policy that steps toward slot 0 using only the observation.
  const double metric = Rollout(world, 4, [&](const Observation& obs) {
    seen.push_back(obs.x);
    const double dx = obs.y[0] - obs.x[0], dy = obs.y[1] - obs.x[1];
    const double n = std::max(1.0, std::hypot(dx, dy));
    return std::vector<float>{static_cast<float>(dx / n), static_cast<float>(dy / n)};
  });
  ASSERT_EQ(seen.size(), 10u);
  EXPECT_EQ(seen[0], (std::vector<float>{static_cast<float>(start.robot[0]),
                                         static_cast<float>(start.robot[1])}));
  const Static2DState& end = world.state();
  EXPECT_NEAR(std::hypot(end.robot[0] - end.objects[0][0], end.robot[1] - end.objects[0][1]),
              std::max(0.0, initial - 10.0), 1e-4);
  EXPECT_DOUBLE_EQ(metric, world.EpisodeMetric());
}

TEST(WorldFactory, BuildsEachWorld) {
  auto d = MakeWorld("dynamic2d", "exact", 2.5, true);
  EXPECT_EQ(d->Name(), "dynamic2d");
  EXPECT_EQ(d->Spec().ToString(), "x 2, y 3x32x32, b 2, u 2");
  const auto* d2 = dynamic_cast<const Dynamic2D*>(d.get());
  ASSERT_NE(d2, nullptr);
  EXPECT_TRUE(d2->options().authors_compat);
  EXPECT_EQ(d2->options().noise_sigma, 2.5);
  auto ds = MakeWorld("dynamic2d-state", "partial", 0.0, false);
  EXPECT_EQ(ds->Name(), "dynamic2d-state");
  EXPECT_EQ(ds->Spec().ToString(), "x 2, y 14, b 1, u 2");
  auto s = MakeWorld("static2d", "distance", 0.0, false);
  EXPECT_EQ(s->Name(), "static2d");
  EXPECT_EQ(s->Spec().ToString(), "x 2, y 6, b 1, u 2");
  // Every world's Name() rebuilds the same kind of world.
  for (const std::string& name : WorldNames()) {
    EXPECT_FALSE(WorldPlacements(name).empty());
    if (WorldNeedsRenderer(name)) continue;  // tests/render builds those with a real renderer
    EXPECT_EQ(MakeWorld(name, "none", 0.0, false)->Name(), name);
  }
}

TEST(WorldFactory, CameraWorldWithoutARendererIsAClearError) {
  try {
    MakeWorld("tabletop", "plate", 0.0, false);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("needs a renderer"));
  }
}

TEST(WorldFactory, UnknownNamesThrowUserErrorListingTheValidOnes) {
  try {
    MakeWorld("dynamic3d", "exact", 0.0, false);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("dynamic3d"));
    EXPECT_THAT(e.what(), HasSubstr("dynamic2d, dynamic2d-state, static2d"));
  }
  EXPECT_THROW(WorldPlacements("nope"), UserError);
  try {
    MakeWorld("static2d", "exact", 0.0, false);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("none, position, distance"));
  }
  try {
    MakeWorld("dynamic2d", "position", 0.0, false);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("exact+random"));
  }
}

}  // namespace
}  // namespace recon::worlds
