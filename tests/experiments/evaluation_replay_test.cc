// Keeping a rollout's replay while evaluating: it records every step and changes no outcome.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <vector>

#include "devices/render/mujoco_renderer.h"
#include "engine/experiments/evaluation.h"
#include "engine/experiments/recipe.h"
#include "engine/learn/learner.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/world_factory.h"

namespace recon::experiments {
namespace {

worlds::CellResources Cell() {
  worlds::CellResources cell;
  cell.renderer_factory = render::MujocoRendererFactory();
  return cell;
}

/// A barely trained Baseline (seeded): its rollouts wander, which is what a replay must follow.
learn::Policy BarelyTrainedPolicy() {
  const std::unique_ptr<worlds::World> world =
      worlds::MakeWorld("tabletop", "none", 0.0, false, Cell());
  const Dataset data = worlds::RecordDemonstrations(*world, {100}, 0);  // seed 100
  const WorldRecipe recipe = RecipeForWorld("tabletop", true);
  learn::TrainConfig train = recipe.train;
  train.method = learn::Method::kBaseline;
  train.steps = 3;
  train.batch_size = 8;
  train.seed = 1;
  learn::Trainer trainer(data, recipe.network, train);
  trainer.Train();
  return trainer.policy();
}

TEST(EvaluationReplayTest, KeptReplayHasEveryStepAndChangesNoOutcome) {
  const learn::Policy policy = BarelyTrainedPolicy();
  const WorldMaker make_world = [] {
    return worlds::MakeWorld("tabletop", "none", 0.0, false, Cell());
  };
  const std::vector<uint64_t> seeds = {11, 12};  // two test scenes
  const std::vector<ScenarioOutcome> plain = EvaluatePolicy(make_world, policy, seeds);
  const std::vector<ScenarioOutcome> kept = EvaluatePolicy(make_world, policy, seeds, true);
  ASSERT_EQ(plain.size(), 2u);
  ASSERT_EQ(kept.size(), 2u);
  worlds::TabletopOptions options;
  options.placement = "none";
  auto viewer =
      std::make_unique<worlds::Tabletop>(options, std::make_unique<render::MujocoRenderer>());
  for (size_t i = 0; i < seeds.size(); ++i) {
    SCOPED_TRACE("scenario " + std::to_string(i));
    EXPECT_EQ(kept[i].metric, plain[i].metric);
    EXPECT_EQ(kept[i].succeeded, plain[i].succeeded);
    EXPECT_EQ(kept[i].details, plain[i].details);
    EXPECT_TRUE(plain[i].replay.empty());
    ASSERT_EQ(kept[i].replay.size(), static_cast<size_t>(worlds::Tabletop::kEpisodeLength) + 1);
    for (const std::vector<double>& state : kept[i].replay) {
      ASSERT_EQ(static_cast<int>(state.size()), viewer->ReplayStateSize());
    }
    // The first state is the scene as reset, the last the end the metric scored.
    viewer->Reset(seeds[i]);
    EXPECT_EQ(kept[i].replay.front(), viewer->ReplayState());
    viewer->ShowReplayState(kept[i].replay.back());
    EXPECT_NEAR(viewer->EpisodeMetric(), kept[i].metric, 1e-9);
    EXPECT_NE(kept[i].replay.front(), kept[i].replay.back()) << "the arm never moved";
  }
}

TEST(EvaluationReplayTest, WorldsWithoutReplayKeepNothing) {
  const std::unique_ptr<worlds::World> world = worlds::MakeWorld("static2d", "none", 0.0, false);
  const Dataset data = worlds::RecordDemonstrations(*world, {1, 2}, 0);  // seeds 1, 2
  const WorldRecipe recipe = RecipeForWorld("static2d", false);
  learn::TrainConfig train = recipe.train;
  train.method = learn::Method::kBaseline;
  train.steps = 2;
  train.seed = 1;
  learn::Trainer trainer(data, recipe.network, train);
  trainer.Train();
  const WorldMaker make_world = [] { return worlds::MakeWorld("static2d", "none", 0.0, false); };
  const std::vector<ScenarioOutcome> kept =
      EvaluatePolicy(make_world, trainer.policy(), {3, 4}, true);
  ASSERT_EQ(kept.size(), 2u);
  for (const ScenarioOutcome& o : kept) EXPECT_TRUE(o.replay.empty());
}

}  // namespace
}  // namespace recon::experiments

namespace recon::experiments {
namespace {

// The hooks a screen uses: a progress call after every step, and a cancel that stops the batch
// before the next step and scores nothing. Neither changes a rollout.
TEST(EvaluationHooksTest, ProgressEveryStepChangesNothingAndCancelStops) {
  const learn::Policy policy = BarelyTrainedPolicy();
  const WorldMaker make_world = [] {
    return worlds::MakeWorld("tabletop", "none", 0.0, false, Cell());
  };
  const std::vector<uint64_t> seeds = {11};
  const std::vector<ScenarioOutcome> plain = EvaluatePolicy(make_world, policy, seeds);
  std::vector<int> reported;
  EvaluationHooks hooks;
  hooks.on_step = [&](int done, int steps) {
    EXPECT_EQ(steps, worlds::Tabletop::kEpisodeLength);
    reported.push_back(done);
  };
  const std::vector<ScenarioOutcome> watched =
      EvaluatePolicy(make_world, policy, seeds, false, hooks);
  ASSERT_EQ(static_cast<int>(reported.size()), worlds::Tabletop::kEpisodeLength);
  for (size_t i = 0; i < reported.size(); ++i) EXPECT_EQ(reported[i], static_cast<int>(i) + 1);
  ASSERT_EQ(watched.size(), 1u);
  EXPECT_EQ(watched[0].metric, plain[0].metric);
  EXPECT_EQ(watched[0].details, plain[0].details);

  // Cancelled after step 5: the sixth never runs.
  std::atomic<bool> cancel{false};
  int last = 0;
  hooks.cancel = &cancel;
  hooks.on_step = [&](int done, int) {
    last = done;
    if (done == 5) cancel = true;
  };
  EXPECT_THROW(EvaluatePolicy(make_world, policy, seeds, false, hooks), EvaluationCancelled);
  EXPECT_EQ(last, 5);
}

}  // namespace
}  // namespace recon::experiments
