// The distractor probe by whole rollouts on a toy task whose answer is known by construction:
// the task is to point at the red object. A policy that reads the red object succeeds wherever
// either object stands; one that confuses the blue object with it fails wherever the red one is
// moved to; places where the task cannot be done at all are left out.

#include "engine/probe/outcome_probe.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>

#include "engine/core/error.h"
#include "tests/probe/toy_scene.h"

namespace recon::probe {
namespace {

using ::testing::HasSubstr;
using testing::RedCentroid;
using testing::TwoObjectWorld;

/// Point at the red object in one step: the action is a place on the table (metres); success
/// when it lands within 8 cm of the red object. The top-left corner (x, y < 0.1 m) is out of
/// reach: with the red object there, the task cannot be done.
class PointAtRed : public TwoObjectWorld {
 public:
  worlds::WorldTraits Traits() const override {
    worlds::WorldTraits traits;
    traits.has_success = true;
    return traits;
  }
  void Reset(uint64_t seed) override {
    TwoObjectWorld::Reset(seed);
    pointed_ = {-1, -1};
  }
  void Step(const std::vector<float>& u) override { pointed_ = {u[0], u[1]}; }
  bool TaskSucceeded() const override {
    const std::array<double, 2> red = ObjectLayout().at("red");
    return std::hypot(pointed_[0] - red[0], pointed_[1] - red[1]) < 0.08;
  }
  bool TaskFeasible() const override {
    const std::array<double, 2> red = ObjectLayout().at("red");
    return !(red[0] < 0.1 && red[1] < 0.1);
  }

 private:
  std::array<double, 2> pointed_ = {-1, -1};
};

/// The centroid of one colour channel's bright pixels, as a table place (metres).
std::vector<float> PlaceOf(const std::vector<float>& y, int channel) {
  constexpr int n = TwoObjectWorld::kSize;
  const std::vector<float> plane(y.begin() + channel * n * n, y.begin() + (channel + 1) * n * n);
  const std::vector<float> px = RedCentroid(plane);  // the centroid of whichever plane is given
  return {(px[0] + 0.5f) / n, (px[1] + 0.5f) / n};   // a square's centre, within 5 cm a side
}

/// A subject that points at the object drawn in `channel` (0 red, 2 blue), rolled out for real:
/// a fresh world per copy, reset, arranged, stepped by its action, judged.
ProbeSubject PointsAt(int channel, const std::string& label) {
  ProbeSubject subject;
  subject.method = label;
  subject.label = label;
  subject.act = [channel](const ProbeSubject::Rows&, const ProbeSubject::Rows& ys) {
    ProbeSubject::Rows out;
    for (const auto& y : ys) out.push_back(PlaceOf(y, channel));
    return out;
  };
  subject.features = subject.act;
  subject.rollouts = [act = subject.act](uint64_t seed, size_t copies,
                                         const ProbeSubject::Arrangement& arrange) {
    std::vector<bool> succeeded;
    for (size_t copy = 0; copy < copies; ++copy) {
      PointAtRed world;
      world.Reset(seed);
      arrange(world, copy);
      const worlds::Observation seen = world.Observe();
      world.Step(act({seen.x}, {seen.y}).front());
      succeeded.push_back(world.TaskSucceeded());
    }
    return succeeded;
  };
  return subject;
}

TEST(OutcomeProbeTest, APolicyThatReadsTheRightObjectStillSucceedsWhereverEitherStands) {
  PointAtRed world;
  ProbeGrid grid;
  grid.nx = grid.ny = 10;
  int last_done = -1, last_total = 0;
  const OutcomeResult result =
      ProbeOutcomes(world, 3, {}, grid, {PointsAt(0, "reads red"), PointsAt(2, "reads blue")},
                    [&](int done, int total) {
                      EXPECT_GT(done, last_done);
                      last_done = done;
                      last_total = total;
                    });
  EXPECT_EQ(last_total, 2 * 100);
  EXPECT_EQ(last_done, last_total);
  ASSERT_EQ(result.objects, (std::vector<std::string>{"blue", "red"}));
  const ObjectOutcome& red_reader_blue = result.outcomes[0][0];
  const ObjectOutcome& red_reader_red = result.outcomes[0][1];
  const ObjectOutcome& blue_reader_red = result.outcomes[1][1];
  // The red reader points at the red object wherever it is, and ignores the blue one.
  EXPECT_TRUE(red_reader_red.home_succeeded);
  EXPECT_DOUBLE_EQ(red_reader_red.success_rate, 1.0);
  EXPECT_DOUBLE_EQ(red_reader_blue.success_rate, 1.0);
  // The blue reader points at the blue object: it fails wherever the red one goes, but for
  // the few places within 8 cm of where it points (beside the blue object).
  EXPECT_FALSE(blue_reader_red.home_succeeded);
  EXPECT_LT(blue_reader_red.success_rate, 0.05);
  // The red object in the top-left corner (the cell centred at (0.05, 0.05)) is out of reach:
  // not rolled out, and counted apart; nor are the places on the blue object.
  EXPECT_EQ(red_reader_red.infeasible, 1);
  EXPECT_TRUE(std::isnan(red_reader_red.succeeded[0]));
  EXPECT_EQ(red_reader_red.succeeded[5 * 10 + 9], 1.0);
  world.Reset(3);
  const size_t free =
      FreePlaces(grid, {0, 1, 0, 1}, *world.PlaceableArea(), world.ObjectLayout(), "red").size();
  EXPECT_EQ(static_cast<size_t>(red_reader_red.places + red_reader_red.infeasible), free);
  EXPECT_LT(free, 100u);
  int rolled = 0;
  for (double v : red_reader_red.succeeded) rolled += std::isnan(v) ? 0 : 1;
  EXPECT_EQ(rolled, red_reader_red.places);
  EXPECT_EQ(world.ObjectLayout().at("red"), (std::array<double, 2>{0.25, 0.28}));
}

TEST(OutcomeProbeTest, RefusesAWorldWithoutSuccessOrASubjectThatCannotRollOutAndCancels) {
  TwoObjectWorld no_success;  // rollouts that neither succeed nor fail
  try {
    ProbeOutcomes(no_success, 1, {}, {}, {PointsAt(0, "reads red")});
    ADD_FAILURE() << "accepted a world without success";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("do not succeed or fail"));
  }
  PointAtRed world;
  ProbeSubject looks_only = PointsAt(0, "looks only");
  looks_only.rollouts = nullptr;
  EXPECT_THROW(ProbeOutcomes(world, 1, {}, {}, {looks_only}), UserError);
  ProbeGrid grid;
  grid.nx = 1;
  EXPECT_THROW(ProbeOutcomes(world, 1, {}, grid, {PointsAt(0, "reads red")}), UserError);
  EXPECT_THROW(ProbeOutcomes(world, 1, {"green"}, {}, {PointsAt(0, "reads red")}), UserError);
  std::atomic<bool> cancel{true};
  EXPECT_THROW(ProbeOutcomes(world, 1, {}, {}, {PointsAt(0, "reads red")}, nullptr, &cancel),
               ProbeCancelled);
}

}  // namespace
}  // namespace recon::probe
