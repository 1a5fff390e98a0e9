// Keeping a rollout's replay while evaluating: it records every step and changes no outcome.

#include <gtest/gtest.h>

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
