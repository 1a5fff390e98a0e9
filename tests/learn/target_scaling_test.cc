#include "engine/learn/target_scaling.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "engine/learn/training_data.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

TEST(TargetScalingTest, FitStandardisesAndRestoreUndoesIt) {
  Dataset data = testing::MakeVectorTask(5, 10, 7);
  for (Episode& e : data.demos) {
    for (Sample& s : e.samples) {
      s.u[0] = 1000.0f * s.u[0] + 40.0f;
      s.u[1] = 3.0f;  // never varies: must keep scale 1, not divide by zero
    }
  }
  TrainingData t = TrainingData::From(data, 1.0f);
  const std::vector<float> raw_u = t.demo_u;
  const TargetScaling scaling = TargetScaling::Fit(t);
  EXPECT_EQ(scaling.u_scale[1], 1.0f);
  EXPECT_FLOAT_EQ(scaling.u_offset[1], 3.0f);
  EXPECT_GT(scaling.u_scale[0], 100.0f);
  scaling.Apply(t);

  // Standardised: mean 0 and spread 1 in the varying dimension, 0 in the constant one.
  double sum = 0, sum_sq = 0;
  const int n = static_cast<int>(t.num_demo);
  for (int i = 0; i < n; ++i) {
    sum += t.demo_u[2 * i];
    sum_sq += t.demo_u[2 * i] * t.demo_u[2 * i];
    EXPECT_EQ(t.demo_u[2 * i + 1], 0.0f);
  }
  EXPECT_NEAR(sum / n, 0.0, 1e-5);
  EXPECT_NEAR(sum_sq / n, 1.0, 1e-4);

  // Restore maps rows (with a stride, like a [mean | logvar] head) back to the raw values.
  std::vector<float> rows;
  for (int i = 0; i < n; ++i)
    rows.insert(rows.end(), {t.demo_u[2 * i], t.demo_u[2 * i + 1], -7, -7});
  scaling.RestoreActions(rows.data(), n, 4);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(rows[4 * i], raw_u[2 * i], 1e-2f * std::abs(raw_u[2 * i]) + 1e-3f);
    EXPECT_FLOAT_EQ(rows[4 * i + 1], 3.0f);
    EXPECT_EQ(rows[4 * i + 2], -7.0f);  // log-variances are not touched
  }
}

TEST(TargetScalingTest, BeaconsAreFittedOnDemosAndPlayTogether) {
  Dataset data = testing::MakeVectorTask(6, 4, 30);
  for (PlaySample& p : data.play) p.b[0] += 50.0f;
  const TrainingData t = TrainingData::From(data, 1.0f);
  const TargetScaling scaling = TargetScaling::Fit(t);
  // 20 demo samples near 0 and 30 play samples near 50: the mean lies between.
  EXPECT_GT(scaling.b_offset[0], 20.0f);
  EXPECT_LT(scaling.b_offset[0], 40.0f);
}

TEST(TargetScalingTest, FlattenRoundTripAndBadSizes) {
  const Dataset data = testing::MakeVectorTask(7, 4, 3);
  const TargetScaling scaling = TargetScaling::Fit(TrainingData::From(data, 1.0f));
  EXPECT_EQ(TargetScaling::Unflatten(data.spec, scaling.Flatten()), scaling);
  std::vector<float> flat = scaling.Flatten();
  flat.pop_back();
  EXPECT_THROW(TargetScaling::Unflatten(data.spec, flat), UserError);
  flat = scaling.Flatten();
  flat[0] = NAN;
  EXPECT_THROW(TargetScaling::Unflatten(data.spec, flat), UserError);
  EXPECT_EQ(TargetScaling::Identity(data.spec).u_scale, std::vector<float>(2, 1.0f));
}

// A lab records joint velocities in mrad/s and beacons in millimetres: the policy must answer in
// those units, with and without standardisation, and a checkpoint must keep them.
TEST(TargetScalingTest, TrainedPolicyAnswersInTheRecordedUnits) {
  Dataset data = testing::MakeVectorTask(8, 30, 20);
  for (Episode& e : data.demos) {
    for (Sample& s : e.samples) {
      for (float& v : s.u) v *= 1000.0f;
      for (float& v : s.b) v = 100.0f * v + 500.0f;
    }
  }
  for (PlaySample& p : data.play) {
    for (float& v : p.b) v = 100.0f * v + 500.0f;
  }
  TrainConfig train;
  train.steps = 1500;
  train.seed = 3;
  Trainer trainer(data, NetworkConfig{}, train);
  trainer.Train();
  const Policy policy = trainer.policy();
  double action_error = 0, beacon_error = 0;
  int n = 0;
  for (const Episode& e : data.demos) {
    for (const Sample& s : e.samples) {
      const std::vector<float> u = policy.Act(s.x, s.y);
      const std::vector<float> b = policy.PredictBeacon(s.x, s.y);
      for (int k = 0; k < 2; ++k) {
        action_error += std::abs(u[k] - s.u[k]);
        beacon_error += std::abs(b[k] - s.b[k]);
      }
      ++n;
    }
  }
  // Targets span about +-1000 and 400..600: errors this small mean the units came back.
  EXPECT_LT(action_error / (2 * n), 100.0);
  EXPECT_LT(beacon_error / (2 * n), 15.0);

  const std::string path = ::testing::TempDir() + "/scaled_units.ckpt";
  trainer.SaveCheckpoint(path);
  const Policy loaded = LoadPolicy(path);
  const Sample& s = data.demos[0].samples[0];
  EXPECT_EQ(loaded.Act(s.x, s.y), policy.Act(s.x, s.y));
  EXPECT_EQ(loaded.PredictBeacon(s.x, s.y), policy.PredictBeacon(s.x, s.y));
}

// Joint angles in degrees around 90 and a vector y in millimetres: with standardize_inputs the
// networks see unit-scale inputs, the policy applies the same scaling when it acts, and
// checkpoints written with or without it read back.
TEST(TargetScalingTest, InputsAreStandardisedForTrainingAndActing) {
  Dataset data = testing::MakeVectorTask(14, 30);
  for (Episode& e : data.demos) {
    for (Sample& s : e.samples) {
      for (float& v : s.x) v = 90.0f + 30.0f * v;
      for (float& v : s.y) v = 1000.0f * v;
    }
  }
  TrainingData stacked = TrainingData::From(data, 1.0f);
  TargetScaling scaling = TargetScaling::Fit(stacked);
  EXPECT_FALSE(scaling.ScalesInputs());
  scaling.FitInputs(stacked);
  ASSERT_TRUE(scaling.ScalesInputs());
  EXPECT_NEAR(scaling.x_offset[0], 90.0f, 6.0f);
  EXPECT_NEAR(scaling.x_scale[0], 30.0f / std::sqrt(3.0f), 3.0f);  // U(-1, 1) * 30
  EXPECT_EQ(scaling.y_offset.size(), 6u);
  std::vector<float> x = {scaling.x_offset[0] + scaling.x_scale[0],
                          scaling.x_offset[1] - 2 * scaling.x_scale[1]};
  std::vector<float> y(6);
  for (int k = 0; k < 6; ++k) y[k] = scaling.y_offset[k] + 0.5f * scaling.y_scale[k];
  scaling.ApplyToInputs(x.data(), y.data());
  EXPECT_NEAR(x[0], 1.0f, 1e-5);
  EXPECT_NEAR(x[1], -2.0f, 1e-5);
  for (float v : y) EXPECT_NEAR(v, 0.5f, 1e-5);
  // Checkpoints: with inputs, and (older, or without) targets only.
  EXPECT_EQ(TargetScaling::Unflatten(data.spec, scaling.Flatten()), scaling);
  const TargetScaling targets_only = TargetScaling::Fit(stacked);
  EXPECT_EQ(TargetScaling::Unflatten(data.spec, targets_only.Flatten()), targets_only);

  TrainConfig train;
  train.steps = 1500;
  train.seed = 4;
  train.standardize_inputs = true;
  Trainer trainer(data, NetworkConfig{}, train);
  trainer.Train();
  // u = 0.5 (y01 / 1000 - (x - 90) / 30): learnable only if acting scales x and y as training did.
  EXPECT_LT(testing::ActionMse(trainer.policy(), data), 0.01);
  const std::string path = ::testing::TempDir() + "/recon_input_scaling.ckpt";
  trainer.SaveCheckpoint(path);
  EXPECT_EQ(testing::Probe(LoadPolicy(path), data), testing::Probe(trainer.policy(), data));
  EXPECT_TRUE(TrainConfigFromJson(ToJson(train)).standardize_inputs);
}

}  // namespace
}  // namespace recon::learn
