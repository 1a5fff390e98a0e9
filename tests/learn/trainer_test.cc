// Training behaviour: learning, determinism (also across threads), divergence, the restart rule,
// cancellation and the observer.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "engine/core/error.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using testing::BitwiseEqual;
using ::testing::HasSubstr;
using testing::MakeImageTask;
using testing::MakeVectorTask;
using testing::Probe;
using testing::SmallImageNet;

TrainConfig Steps(int steps, uint64_t seed = 1) {
  TrainConfig t;
  t.steps = steps;
  t.seed = seed;
  return t;
}

// Probe of a policy trained from scratch on `data`.
std::vector<float> TrainAndProbe(const Dataset& data, const NetworkConfig& network,
                                 const TrainConfig& train) {
  Trainer trainer(data, network, train);
  trainer.Train();
  return Probe(trainer.policy(), data);
}

TEST(TrainerTest, TrainingLowersTheLoss) {
  const Dataset data = MakeVectorTask(3, 20);
  Trainer trainer(data, NetworkConfig{}, Steps(1500));
  std::vector<float> losses;
  trainer.SetObserver([&](const StepMetrics& m) { losses.push_back(m.action_loss); });
  const TrainResult result = trainer.Train();
  ASSERT_EQ(losses.size(), 1500u);
  double first = 0, last = 0;
  for (int i = 0; i < 50; ++i) {
    first += losses[i];
    last += losses[losses.size() - 1 - i];
  }
  // NLL can go negative as the variance shrinks: require a large absolute drop.
  EXPECT_LT(last / 50, first / 50 - 2.0);
  EXPECT_EQ(result.steps_run, 1500);
  EXPECT_FALSE(result.cancelled);

  // The mean action is close to the expert's on the training data.
  EXPECT_LT(testing::ActionMse(trainer.policy(), data), 0.01);
}

TEST(TrainerTest, SameSeedGivesBitwiseSameModelAndOtherSeedDoesNot) {
  const Dataset data = MakeImageTask(5, 24, 16, 6);
  TrainConfig train = AuthorsRecipe();
  train.steps = 30;
  train.restart_rule = false;
  const std::vector<float> a = TrainAndProbe(data, SmallImageNet(), train);
  const std::vector<float> b = TrainAndProbe(data, SmallImageNet(), train);
  EXPECT_TRUE(BitwiseEqual(a, b));
  train.seed = 2;
  EXPECT_FALSE(BitwiseEqual(a, TrainAndProbe(data, SmallImageNet(), train)));

  // ActBatch gives the same actions as Act, row by row.
  Trainer trainer(data, SmallImageNet(), train);
  trainer.Train();
  const Policy policy = trainer.policy();
  std::vector<std::vector<float>> xs, ys;
  for (const Sample& s : data.demos[0].samples) {
    xs.push_back(s.x);
    ys.push_back(s.y);
  }
  const std::vector<std::vector<float>> batch = policy.ActBatch(xs, ys);
  ASSERT_EQ(batch.size(), xs.size());
  for (size_t i = 0; i < xs.size(); ++i) {
    const std::vector<float> one = policy.Act(xs[i], ys[i]);
    ASSERT_EQ(one.size(), 2u);
    EXPECT_NEAR(batch[i][0], one[0], 1e-5);
    EXPECT_NEAR(batch[i][1], one[1], 1e-5);
  }
}

TEST(TrainerTest, ConcurrentTrainersMatchSequentialOnes) {
  const Dataset data = MakeImageTask(6, 24, 16, 6);
  TrainConfig first = AuthorsRecipe(), second = AuthorsRecipe();
  first.steps = second.steps = 40;
  first.restart_rule = second.restart_rule = false;
  second.seed = 9;
  second.method = Method::kBaseline;
  const std::vector<float> a = TrainAndProbe(data, SmallImageNet(), first);
  const std::vector<float> b = TrainAndProbe(data, SmallImageNet(), second);
  std::vector<float> a2, b2;
  std::thread ta([&] { a2 = TrainAndProbe(data, SmallImageNet(), first); });
  std::thread tb([&] { b2 = TrainAndProbe(data, SmallImageNet(), second); });
  ta.join();
  tb.join();
  EXPECT_TRUE(BitwiseEqual(a, a2));
  EXPECT_TRUE(BitwiseEqual(b, b2));
}

TEST(TrainerTest, DivergenceStopsBeforeTheWeightsAreTouched) {
  {
    SCOPED_TRACE("a learning rate of 1e30");
    const Dataset data = MakeVectorTask(1, 5);
    TrainConfig train = Steps(50);
    train.learning_rate = 1e30;
    Trainer trainer(data, NetworkConfig{}, train);
    std::vector<float> after_last_good_step;
    trainer.SetObserver(
        [&](const StepMetrics&) { after_last_good_step = Probe(trainer.policy(), data, 2); });
    try {
      trainer.Train();
      FAIL() << "expected DivergenceError";
    } catch (const DivergenceError& e) {
      EXPECT_EQ(e.step(), trainer.step());
      EXPECT_THAT(e.what(), HasSubstr("step " + std::to_string(e.step())));
      EXPECT_GT(e.step(), 0);
    }
    EXPECT_TRUE(BitwiseEqual(Probe(trainer.policy(), data, 2), after_last_good_step));
  }
  {
    SCOPED_TRACE("finite targets whose squared error overflows");
    Dataset data = MakeVectorTask(1, 5);
    for (Episode& e : data.demos) {
      for (Sample& s : e.samples) s.u = {3e38f, -3e38f};
    }
    // On raw targets (standardised ones would map these constants to 0 and never overflow).
    TrainConfig train = Steps(10);
    train.standardize_targets = false;
    Trainer trainer(data, NetworkConfig{}, train);
    const std::vector<float> before = Probe(trainer.policy(), data, 2);
    try {
      trainer.Train();
      FAIL() << "expected DivergenceError";
    } catch (const DivergenceError& e) {
      EXPECT_EQ(e.step(), 0);
    }
    EXPECT_EQ(trainer.step(), 0);
    EXPECT_TRUE(BitwiseEqual(Probe(trainer.policy(), data, 2), before));
  }
}

TEST(TrainerTest, BaselineIgnoresBeaconsAndReconUsesThem) {
  const Dataset data = MakeVectorTask(2, 10, 5);
  Dataset moved = data;
  for (Episode& e : moved.demos) {
    for (Sample& s : e.samples) s.b = {s.b[1] * 3.0f, -s.b[0]};
  }
  for (PlaySample& p : moved.play) p.b[0] += 1.0f;
  TrainConfig train = AuthorsRecipe();
  train.steps = 60;
  train.restart_rule = false;
  train.method = Method::kBaseline;
  EXPECT_TRUE(BitwiseEqual(TrainAndProbe(data, NetworkConfig{}, train),
                           TrainAndProbe(moved, NetworkConfig{}, train)));
  train.method = Method::kRecon;
  EXPECT_FALSE(BitwiseEqual(TrainAndProbe(data, NetworkConfig{}, train),
                            TrainAndProbe(moved, NetworkConfig{}, train)));
}

TEST(TrainerTest, BeaconNetLearnsALearnableBeacon) {
  const Dataset data = MakeVectorTask(4, 20, 40);
  Trainer trainer(data, NetworkConfig{}, Steps(2500));
  trainer.Train();
  const Policy policy = trainer.policy();
  const Dataset fresh = MakeVectorTask(99, 10);
  double error = 0;
  int n = 0;
  for (const Episode& e : fresh.demos) {
    for (const Sample& s : e.samples) {
      const std::vector<float> b = policy.PredictBeacon(s.x, s.y);
      ASSERT_EQ(b.size(), 2u);
      for (int i = 0; i < 2; ++i, ++n) error += (b[i] - s.b[i]) * (b[i] - s.b[i]);
    }
  }
  // b is uniform in [-1, 1] (variance 1/3): a good fit is far below that.
  EXPECT_LT(error / n, 0.01);

  TrainConfig baseline = Steps(5);
  baseline.method = Method::kBaseline;
  Trainer base(data, NetworkConfig{}, baseline);
  base.Train();
  const Sample& s = data.demos[0].samples[0];
  EXPECT_TRUE(base.policy().PredictBeacon(s.x, s.y).empty());
  EXPECT_EQ(base.policy().Features(s.x, s.y).size(), 6u);
}

TEST(TrainerTest, CancelStopsEarlyAndTrainingCanContinue) {
  const Dataset data = MakeVectorTask(1, 5);
  Trainer trainer(data, NetworkConfig{}, Steps(100));
  std::atomic<bool> cancel{false};
  trainer.SetObserver([&](const StepMetrics& m) {
    if (m.step == 9) cancel = true;
  });
  const TrainResult stopped = trainer.Train(&cancel);
  EXPECT_TRUE(stopped.cancelled);
  EXPECT_EQ(stopped.steps_run, 10);
  EXPECT_EQ(trainer.step(), 10);
  cancel = false;
  const TrainResult done = trainer.Train(&cancel);
  EXPECT_FALSE(done.cancelled);
  EXPECT_EQ(done.steps_run, 100);
  EXPECT_EQ(done.final_metrics.step, 99);
}

TEST(TrainerTest, RestartRuleRetriesHopelessRuns) {
  // Actions that are pure noise cannot be fitted: the action error stays near their variance.
  Dataset noise = MakeVectorTask(8, 10);
  Rng rng(3);
  for (Episode& e : noise.demos) {
    for (Sample& s : e.samples) s.u = {static_cast<float>(rng.Normal()), 0.0f};
  }
  TrainConfig train = AuthorsRecipe();
  train.steps = 30;
  train.max_attempts = 3;
  Trainer trainer(noise, NetworkConfig{}, train);
  std::vector<int> attempts_seen;
  trainer.SetObserver([&](const StepMetrics& m) {
    if (m.step == 0) attempts_seen.push_back(m.attempt);
  });
  const TrainResult result = trainer.Train();
  EXPECT_EQ(result.attempts, 3);
  EXPECT_EQ(attempts_seen, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(result.final_metrics.attempt, 2);

  // A generous threshold accepts the first attempt; without the rule there is one attempt.
  train.restart_action_threshold = 1e9;
  train.restart_beacon_threshold = 1e9;
  EXPECT_EQ(Trainer(noise, NetworkConfig{}, train).Train().attempts, 1);
  train.restart_action_threshold = 0.1;
  train.restart_rule = false;
  EXPECT_EQ(Trainer(noise, NetworkConfig{}, train).Train().attempts, 1);
}

TEST(TrainerTest, ObserverSeesEveryStepInOrder) {
  const Dataset data = MakeImageTask(2, 12, 16, 4);
  TrainConfig train = AuthorsRecipe();
  train.steps = 25;
  train.restart_rule = false;
  Trainer trainer(data, SmallImageNet(), train);
  std::vector<StepMetrics> seen;
  trainer.SetObserver([&](const StepMetrics& m) { seen.push_back(m); });
  const TrainResult result = trainer.Train();
  ASSERT_EQ(seen.size(), 25u);
  for (int i = 0; i < 25; ++i) {
    EXPECT_EQ(seen[i].step, i);
    EXPECT_EQ(seen[i].attempt, 0);
    EXPECT_GT(seen[i].play_loss, 0.0f);  // play data is used for RECON
    EXPECT_NEAR(seen[i].total_loss,
                seen[i].action_loss + 1.2f * seen[i].beacon_loss + 1.2f * seen[i].play_loss,
                1e-4f * std::abs(seen[i].total_loss));
  }
  EXPECT_EQ(result.final_metrics.step, 24);
  EXPECT_EQ(result.final_metrics.total_loss, seen.back().total_loss);
}

}  // namespace
}  // namespace recon::learn
