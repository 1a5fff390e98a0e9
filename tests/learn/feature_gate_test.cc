// The feature gate (NetworkConfig::feature_gate_hidden): trained against either kind of target
// (GateTarget), it shuts the features out of the states where the teacher's action does not
// depend on them, and stays open where it does.

#include <gtest/gtest.h>

#include "engine/core/rng.h"
#include "engine/learn/learner.h"

namespace recon::learn {
namespace {

// x = (phase, s), y = 6 numbers. In phase -1 the teacher's action is a function of s alone (an
// approach that is the same in every scene); in phase +1 it is y's first two numbers (where
// the plate is). Nothing but the phase tells the two apart.
Dataset PhaseTask(uint64_t seed) {
  Rng rng(seed);
  Dataset data;
  data.spec = DataSpec{2, {6}, 0, 2};
  for (int e = 0; e < 40; ++e) {
    Episode episode;
    for (int t = 0; t < 10; ++t) {
      Sample s;
      const float phase = t < 5 ? -1.0f : 1.0f;
      const float along = static_cast<float>(rng.Uniform(-1, 1));
      s.x = {phase, along};
      for (int i = 0; i < 6; ++i) s.y.push_back(static_cast<float>(rng.Uniform(-1, 1)));
      s.u = phase < 0 ? std::vector<float>{0.5f * along, -0.3f * along}
                      : std::vector<float>{s.y[0], s.y[1]};
      episode.samples.push_back(s);
    }
    data.demos.push_back(episode);
  }
  return data;
}

double MeanGate(const Policy& policy, const Dataset& data, float phase) {
  double sum = 0;
  int n = 0;
  for (const Episode& e : data.demos) {
    for (const Sample& s : e.samples) {
      if (s.x[0] != phase) continue;
      const float g = policy.FeatureGate(s.x, s.y);
      EXPECT_GE(g, 0.0f);
      EXPECT_LE(g, 1.0f);
      sum += g;
      ++n;
    }
  }
  return sum / n;
}

TrainConfig GateTraining(double margin) {
  TrainConfig train;
  train.method = Method::kBaseline;
  train.steps = 3000;
  train.learning_rate = 1e-3;
  train.seed = 3;
  train.gate_margin = margin;
  return train;
}

NetworkConfig GatedNetwork() {
  NetworkConfig network;
  network.feature_mlp_hidden = {32, 32};
  network.policy_hidden = {64, 64};
  network.feature_gate_hidden = {16};
  return network;
}

TEST(FeatureGateTest, ShutsWhereTheActionIgnoresTheFeaturesAndOpensWhereItNeedsThem) {
  const Dataset data = PhaseTask(1);
  const NetworkConfig network = GatedNetwork();
  // The features are worth several nats per sample in phase +1 and nothing in phase -1 (which
  // x alone predicts); a margin of 2 nats lies between.
  Trainer trainer(data, network, GateTraining(2.0));
  trainer.Train();
  const double approach = MeanGate(trainer.policy(), data, -1.0f);
  const double delivery = MeanGate(trainer.policy(), data, 1.0f);
  EXPECT_LT(approach, 0.2) << "phase -1 does not need the features";
  EXPECT_GT(delivery, 0.8) << "phase +1 does";
}

TEST(FeatureGateTest, AMarginAboveWhatTheFeaturesAreWorthShutsItEverywhere) {
  const Dataset data = PhaseTask(1);
  const NetworkConfig network = GatedNetwork();
  Trainer trainer(data, network, GateTraining(20.0));
  trainer.Train();
  EXPECT_LT(MeanGate(trainer.policy(), data, 1.0f), 0.2);
  EXPECT_LT(MeanGate(trainer.policy(), data, -1.0f), 0.2);
}

// Episodes in time, as demonstrations are: x = (phase, t), y = 6 numbers fixed for the episode
// (the first two: where the plate is). In phase -1 (the first 10 steps) the action is a
// function of t, the same in every episode; in phase +1 it heads for the plate.
Dataset PlateTask(uint64_t seed) {
  Rng rng(seed);
  Dataset data;
  data.spec = DataSpec{2, {6}, 0, 2};
  for (int e = 0; e < 40; ++e) {
    std::vector<float> y;
    for (int i = 0; i < 6; ++i) y.push_back(static_cast<float>(rng.Uniform(-1, 1)));
    Episode episode;
    for (int t = 0; t < 20; ++t) {
      Sample s;
      const float phase = t < 10 ? -1.0f : 1.0f, time = 0.05f * static_cast<float>(t);
      s.x = {phase, time};
      s.y = y;
      s.u = phase < 0 ? std::vector<float>{0.5f * time, -0.3f * time}
                      : std::vector<float>{y[0], y[1]};
      episode.samples.push_back(s);
    }
    data.demos.push_back(episode);
  }
  return data;
}

TEST(FeatureGateTest, TargetsByDisagreementShutItWhereEveryTeacherAgrees) {
  // In phase -1 every episode does the same at the same state; in phase +1 the episodes'
  // plates differ, by about 2 units of the actions' variance on average.
  const Dataset data = PlateTask(1);
  TrainConfig train = GateTraining(0.5);
  train.gate_target = GateTarget::kDisagreement;
  Trainer trainer(data, GatedNetwork(), train);
  trainer.Train();
  EXPECT_LT(MeanGate(trainer.policy(), data, -1.0f), 0.2);
  EXPECT_GT(MeanGate(trainer.policy(), data, 1.0f), 0.8);
  // Routed: where the gate shuts, the blind branch alone learnt the actions, and it does them.
  const Sample& early = data.demos[3].samples[4];
  EXPECT_NEAR(trainer.policy().Act(early.x, early.y)[0], early.u[0], 0.05);
}

TEST(FeatureGateTest, WithoutAGateThePolicyReadsEveryFeature) {
  const Dataset data = PhaseTask(2);
  NetworkConfig network;
  network.feature_mlp_hidden = {8};
  network.policy_hidden = {8};
  Trainer trainer(data, network, GateTraining(0.0));
  trainer.Train();
  EXPECT_EQ(trainer.policy().FeatureGate(data.demos[0].samples[0].x, data.demos[0].samples[0].y),
            1.0f);
}

}  // namespace
}  // namespace recon::learn
