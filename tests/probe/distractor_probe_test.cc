// The distractor probe on a toy world whose answer is known by construction: a policy that
// reads only the red object moves with it and not with the blue one; and on the simulated
// tabletop, where a policy that reads only the bowl's colour is found to look at the bowl.

#include "engine/probe/distractor_probe.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "engine/core/error.h"
#include "tests/probe/toy_scene.h"

namespace recon::probe {
namespace {

using ::testing::HasSubstr;
using testing::ReadsOnlyRed;
using testing::TwoObjectWorld;

/// A subject that ignores the image altogether.
ProbeSubject Blind() {
  ProbeSubject subject;
  subject.method = "blind";
  subject.label = "Blind";
  subject.act = [](const ProbeSubject::Rows& xs, const ProbeSubject::Rows&) {
    return ProbeSubject::Rows(xs.size(), std::vector<float>{1.0f, 2.0f});
  };
  subject.features = subject.act;
  return subject;
}

TEST(DistractorProbeTest, FindsTheObjectAPolicyReadsAndNotTheOther) {
  TwoObjectWorld world;
  ProbeGrid grid;
  grid.nx = grid.ny = 8;
  int last_done = 0, last_total = 0;
  const ProbeResult result =
      ProbeObjects(world, 3, {}, grid, {ReadsOnlyRed(), Blind()}, [&](int done, int total) {
        EXPECT_EQ(done, last_done + 1);
        last_done = done;
        last_total = total;
      });
  EXPECT_EQ(last_total, 2 * 8 * 8);
  EXPECT_EQ(last_done, last_total);
  ASSERT_EQ(result.objects, (std::vector<std::string>{"blue", "red"}));
  ASSERT_EQ(result.probes.size(), 2u);
  const ObjectProbe& blue = result.probes[0][0];
  const ObjectProbe& red = result.probes[0][1];
  // The red reader's action follows the red object: the centroid moves 20 px per metre, so about
  // 2 px per 10 cm of motion (less where the square is clamped at the image's edge).
  EXPECT_GT(red.action_change_per_10cm, 1.5);
  EXPECT_LT(red.action_change_per_10cm, 2.5);
  EXPECT_DOUBLE_EQ(blue.action_change_per_10cm, 0.0);
  EXPECT_DOUBLE_EQ(blue.feature_change_per_10cm, 0.0);
  EXPECT_GT(red.feature_change_per_10cm, 1.5);
  // The heat map: larger far from home, NaN where the red object would cover the blue one.
  ASSERT_EQ(red.action_change.size(), 64u);
  EXPECT_EQ(red.home, (std::array<double, 2>{0.25, 0.28}));
  int skipped = 0;
  for (double v : red.action_change) skipped += std::isnan(v) ? 1 : 0;
  // The four cells around the blue object at (0.75, 0.75) are 8.8 cm from it, under the two
  // radii (10 cm).
  EXPECT_EQ(skipped, 4);
  for (int cell : {5 * 8 + 5, 5 * 8 + 6, 6 * 8 + 5, 6 * 8 + 6}) {
    EXPECT_TRUE(std::isnan(red.action_change[static_cast<size_t>(cell)])) << cell;
  }
  EXPECT_GT(red.action_change[7 * 8 + 7], red.action_change[2 * 8 + 2]);
  // A policy that reads no image moves with nothing.
  for (const ObjectProbe& p : result.probes[1]) EXPECT_DOUBLE_EQ(p.action_change_per_10cm, 0.0);
  // The scene was reset for each object and once more at the end.
  EXPECT_EQ(world.resets(), 4);
  EXPECT_EQ(world.ObjectLayout().at("red"), (std::array<double, 2>{0.25, 0.28}));
}

TEST(DistractorProbeTest, ALargeGridIsMeasuredInChunksAndAnObjectAskedTwiceOnce) {
  TwoObjectWorld world;
  ProbeGrid grid;
  grid.nx = grid.ny = 20;  // 400 places: more than one chunk of 256
  const ProbeResult result = ProbeObjects(world, 3, {"red", "red"}, grid, {ReadsOnlyRed()});
  ASSERT_EQ(result.objects, (std::vector<std::string>{"red"}));
  ASSERT_EQ(result.probes[0].size(), 1u);
  const ObjectProbe& red = result.probes[0][0];
  int measured = 0;
  for (double v : red.action_change) measured += std::isnan(v) ? 0 : 1;
  EXPECT_GT(measured, 380);  // every place but those around the blue object
  EXPECT_GT(red.action_change_per_10cm, 1.5);
  EXPECT_LT(red.action_change_per_10cm, 2.5);
  // The last cell (the far corner) was measured in the second chunk, against the same home.
  EXPECT_GT(red.action_change.back(), red.action_change.front());
}

TEST(DistractorProbeTest, RefusesBadInputByNameBeforeRenderingAnything) {
  TwoObjectWorld world;
  const auto refused = [&](const std::vector<std::string>& objects, const ProbeGrid& grid,
                           const std::string& words) {
    try {
      ProbeObjects(world, 1, objects, grid, {ReadsOnlyRed()});
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr(words));
    }
  };
  refused({"green"}, {}, "no object \"green\" (valid: blue, red)");
  ProbeGrid grid;
  grid.nx = 1;
  refused({}, grid, "2 to 100 places per side, got 1 x 10");
  grid = {};
  grid.bounds = {0.2, 1.4, 0.0, 1.0};
  refused({}, grid, "leaves the table: objects go at x 0.00 to 1.00 m and y 0.00 to 1.00 m");
  grid.bounds = {0.5, 0.4, 0.0, 1.0};
  refused({}, grid, "bounds are empty");
  grid.bounds = {0.1, NAN, 0.0, 1.0};
  refused({}, grid, "finite");
  EXPECT_THROW(ProbeObjects(world, 1, {}, {}, {}), UserError);
  // A world that cannot move its objects says the probe needs a simulated scene.
  class Fixed : public TwoObjectWorld {
    std::optional<worlds::ObjectArea> PlaceableArea() const override { return std::nullopt; }
  } fixed;
  try {
    ProbeObjects(fixed, 1, {}, {}, {ReadsOnlyRed()});
    ADD_FAILURE() << "a fixed world was probed";
  } catch (const UserError& e) {
    EXPECT_THAT(
        e.what(),
        HasSubstr("the probe moves objects over a table, which the two-objects world cannot do"));
  }
}

TEST(DistractorProbeTest, StopsWhenCancelled) {
  TwoObjectWorld world;
  std::atomic<bool> cancel{false};
  EXPECT_THROW(ProbeObjects(
                   world, 1, {}, {}, {ReadsOnlyRed()},
                   [&](int done, int) {
                     if (done == 30) cancel = true;
                   },
                   &cancel),
               ProbeCancelled);
}

}  // namespace
}  // namespace recon::probe
