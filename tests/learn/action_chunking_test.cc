// Action chunking (ACT): chunked targets, training and acting on chunks, and the temporal
// ensemble of overlapping predictions.

#include "engine/learn/action_ensembler.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "engine/learn/trainer_impl.h"
#include "engine/learn/training_data.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

TEST(ActionChunkingTest, EnsemblingWeightsFavourTheOldestPredictionAsActDoes) {
  const ActionEnsembler ensembler(4, 2, 0.01);
  const std::vector<double> w = ensembler.Weights(3);
  ASSERT_EQ(w.size(), 3u);
  const double sum = 1 + std::exp(-0.01) + std::exp(-0.02);
  EXPECT_NEAR(w[0], 1 / sum, 1e-12);
  EXPECT_NEAR(w[1], std::exp(-0.01) / sum, 1e-12);
  EXPECT_NEAR(w[2], std::exp(-0.02) / sum, 1e-12);
  const std::vector<double> flat = ActionEnsembler(4, 2, 0.0).Weights(2);
  EXPECT_DOUBLE_EQ(flat[0], 0.5);
}

TEST(ActionChunkingTest, EachStepAveragesThePredictionsMadeForIt) {
  const double m = 0.5;  // strong enough that a wrong weight order shows
  ActionEnsembler e(3, 1, m);
  // Predictions made at steps 0, 1, 2, 3 for the next three steps.
  EXPECT_FLOAT_EQ(e.Step({1, 2, 3})[0], 1.0f);
  const double a = 1, b = std::exp(-m), c = std::exp(-2 * m);
  EXPECT_NEAR(e.Step({10, 20, 30})[0], (a * 2 + b * 10) / (a + b), 1e-5);
  EXPECT_NEAR(e.Step({100, 200, 300})[0], (a * 3 + b * 20 + c * 100) / (a + b + c), 1e-4);
  // Step 0's prediction has run out: steps 1, 2, 3 predicted step 3.
  EXPECT_NEAR(e.Step({1000, 2000, 3000})[0], (a * 30 + b * 200 + c * 1000) / (a + b + c), 1e-3);
  e.Reset();
  EXPECT_FLOAT_EQ(e.Step({7, 8, 9})[0], 7.0f);
  EXPECT_THROW(e.Step({1, 2}), UserError);
  EXPECT_THROW(ActionEnsembler(0, 1), UserError);
  EXPECT_THROW(ActionEnsembler(2, 1, -1.0), UserError);
}

TEST(ActionChunkingTest, ActionsLeftOutOfTheEnsembleComeFromTheNewestPrediction) {
  // Two actions per step (a joint velocity, a gripper command); only the gripper is averaged.
  ActionEnsembler e(3, 2, 0.0, {1});
  // Each prediction: (joint, gripper) for this step, the next and the one after.
  std::vector<float> first = e.Step({1, 0, 2, 0, 3, 1});
  EXPECT_FLOAT_EQ(first[0], 1.0f);
  EXPECT_FLOAT_EQ(first[1], 0.0f);
  // Step 1: the joint is the newest prediction's (5), the gripper the mean of 0 and 1.
  std::vector<float> second = e.Step({5, 1, 6, 1, 7, 1});
  EXPECT_FLOAT_EQ(second[0], 5.0f);
  EXPECT_FLOAT_EQ(second[1], 0.5f);
  // Step 2: three predictions (1, 1, 1) for the gripper, the newest's 9 for the joint.
  std::vector<float> third = e.Step({9, 1, 9, 1, 9, 1});
  EXPECT_FLOAT_EQ(third[0], 9.0f);
  EXPECT_FLOAT_EQ(third[1], (1.0f + 1.0f + 1.0f) / 3.0f);
  // With every action ensembled (the default), the joint would have been (3 + 6 + 9) / 3.
  ActionEnsembler all(3, 2, 0.0);
  all.Step({1, 0, 2, 0, 3, 1});
  all.Step({5, 1, 6, 1, 7, 1});
  EXPECT_FLOAT_EQ(all.Step({9, 1, 9, 1, 9, 1})[0], 6.0f);
  EXPECT_THROW(ActionEnsembler(3, 2, 0.0, {2}), UserError);
  EXPECT_THROW(ActionEnsembler(3, 2, 0.0, {-1}), UserError);
}

TEST(ActionChunkingTest, AnEnsembledActionMustBeOneOfThePoliciesActions) {
  NetworkConfig network;
  network.action_chunk = 4;
  network.ensembled_actions = {0, 3};
  const DataSpec spec{1, {1}, 0, 2};
  try {
    BuildArchitecture(spec, network, Method::kBaseline);
    ADD_FAILURE() << "an action outside u was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(),
                ::testing::HasSubstr("ensembled_actions: 3 is not an action (u has 2: 0-1)"));
  }
  network.ensembled_actions = {1, 1};
  EXPECT_THROW(BuildArchitecture(spec, network, Method::kBaseline), UserError);
  network.ensembled_actions = {1};
  EXPECT_NO_THROW(BuildArchitecture(spec, network, Method::kBaseline));
  // The choice travels with the model's configuration; older configurations read as "all".
  EXPECT_EQ(NetworkConfigFromJson(ToJson(network)).ensembled_actions, std::vector<int>{1});
}

TEST(ActionChunkingTest, TargetsAreTheNextActionsWithTheLastRepeated) {
  Dataset data;
  data.spec = DataSpec{1, {1}, 0, 1};
  for (int e = 0; e < 2; ++e) {
    Episode episode;
    for (int t = 0; t < 3; ++t) episode.samples.push_back({{0.0f}, {0.0f}, {}, {10.0f * e + t}});
    data.demos.push_back(episode);
  }
  const TrainingData t = TrainingData::From(data, 1.0f, 2);
  EXPECT_EQ(t.demo_u, (std::vector<float>{0, 1, 1, 2, 2, 2, 10, 11, 11, 12, 12, 12}));
  EXPECT_EQ(TrainingData::From(data, 1.0f).demo_u, (std::vector<float>{0, 1, 2, 10, 11, 12}));
}

TEST(ActionChunkingTest, AChunkedPolicyLearnsAndActsOnChunks) {
  const Dataset data = testing::MakeVectorTask(17, 30);
  NetworkConfig network;
  network.action_chunk = 3;
  TrainConfig train;
  train.steps = 1500;
  train.seed = 2;
  Trainer trainer(data, network, train);
  trainer.Train();
  const Policy policy = trainer.policy();
  EXPECT_EQ(policy.action_chunk(), 3);
  const Sample& s = data.demos[0].samples[0];
  const std::vector<std::vector<float>> chunk = policy.ActChunkBatch({s.x}, {s.y});
  ASSERT_EQ(chunk[0].size(), 6u);
  const std::vector<float> first = policy.Act(s.x, s.y);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_FLOAT_EQ(first[0], chunk[0][0]);
  EXPECT_FLOAT_EQ(first[1], chunk[0][1]);
  // The task's actions are a function of the current sample: the first action is learnt well.
  EXPECT_LT(testing::ActionMse(policy, data), 0.02);
  EXPECT_EQ(NetworkConfigFromJson(ToJson(network)).action_chunk, 3);
  const std::string path = ::testing::TempDir() + "/recon_chunk.ckpt";
  trainer.SaveCheckpoint(path);
  EXPECT_EQ(LoadPolicy(path).ActChunkBatch({s.x}, {s.y}), chunk);
}

TEST(ActionChunkingTest, BothBackendsScoreAChunkPerActionAlike) {
  const Dataset data = testing::MakeImageTask(18, 24, 16, 6);
  NetworkConfig network = testing::SmallImageNet();
  network.action_chunk = 4;
  TrainConfig train;
  train.seed = 3;
  TrainerImpl fused(data, network, train);
  train.backend = Backend::kTorch;
  TrainerImpl torch(data, network, train);
  fused.Step();
  torch.Step();
  EXPECT_NEAR(fused.State().last.action_loss, torch.State().last.action_loss,
              1e-5 * std::abs(fused.State().last.action_loss));
  EXPECT_NEAR(fused.State().last.total_loss, torch.State().last.total_loss,
              1e-5 * std::abs(fused.State().last.total_loss));
  // Per action: a chunk of 4 starts near the single action's loss, not 4 times it.
  network.action_chunk = 1;
  train.backend = Backend::kFused;
  TrainerImpl single(data, network, train);
  single.Step();
  EXPECT_LT(std::abs(fused.State().last.action_loss),
            2.5 * std::abs(single.State().last.action_loss) + 1);
}

}  // namespace
}  // namespace recon::learn
