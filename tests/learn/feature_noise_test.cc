// Feature noise on the policy's input (TrainConfig::feature_noise): the offsets, their draws,
// what training with them changes and what it must not.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/augmentation.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::HasSubstr;

TEST(FeatureNoiseTest, OffsetsAreTheDrawsTimesEachFeaturesSpreadOverTheBatch) {
  // 4 samples x 3 features: feature 0 takes 1, 3, 1, 3 (sd 1), feature 1 is constant (sd 0),
  // feature 2 takes -2, 2, -2, 2 (sd 2).
  const std::vector<float> phi = {1, 5, -2, 3, 5, 2, 1, 5, -2, 3, 5, 2};
  const std::vector<float> noise = {0.5f, 1, -1, 2, -3, 0.25f, -1, 4, 1, 0, 1, -0.5f};
  std::vector<float> offsets(phi.size(), 99.0f);
  FeatureNoiseOffsets(phi.data(), 4, 3, 0.5, noise.data(), offsets.data());
  const double sd[3] = {1, 0, 2};
  for (int b = 0; b < 4; ++b) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(offsets[b * 3 + i], 0.5 * sd[i] * noise[b * 3 + i], 1e-6) << b << "," << i;
    }
  }
}

TrainConfig NoiseConfig(double noise) {
  TrainConfig train;
  train.steps = 60;
  train.seed = 9;
  train.feature_noise = noise;
  return train;
}

TEST(FeatureNoiseTest, TrainingWithNoiseIsReproducibleAndDiffersFromWithout) {
  const Dataset data = testing::MakeImageTask(11, 24, 16, 6);
  auto run = [&](const TrainConfig& train) {
    Trainer trainer(data, testing::SmallImageNet(), train);
    trainer.Train();
    return testing::Probe(trainer.policy(), data);
  };
  const std::vector<float> noisy = run(NoiseConfig(0.5));
  EXPECT_TRUE(testing::BitwiseEqual(noisy, run(NoiseConfig(0.5))));
  EXPECT_FALSE(testing::BitwiseEqual(noisy, run(NoiseConfig(0.0))));
  EXPECT_FALSE(testing::BitwiseEqual(noisy, run(NoiseConfig(1.0))));
}

TEST(FeatureNoiseTest, TheBeaconNetReadsTheFeaturesClean) {
  // At step 0 the weights are the same with or without noise: the beacon loss must be too (the
  // noise is on the policy's input only), the action loss must not.
  const Dataset data = testing::MakeImageTask(14, 24, 16, 6);
  auto first_step = [&](double noise) {
    TrainConfig train = NoiseConfig(noise);
    train.steps = 1;
    Trainer trainer(data, testing::SmallImageNet(), train);
    StepMetrics first;
    trainer.SetObserver([&](const StepMetrics& m) { first = m; });
    trainer.Train();
    return first;
  };
  const StepMetrics clean = first_step(0.0), noisy = first_step(2.0);
  EXPECT_EQ(clean.beacon_loss, noisy.beacon_loss);
  EXPECT_EQ(clean.play_loss, noisy.play_loss);
  EXPECT_NE(clean.action_loss, noisy.action_loss);
}

TEST(FeatureNoiseTest, ACheckpointResumesTheNoiseBitwise) {
  EXPECT_TRUE(testing::ResumedRunMatchesUninterrupted(
      testing::MakeImageTask(12, 24, 16, 6), testing::SmallImageNet(), NoiseConfig(0.7),
      ::testing::TempDir() + "/recon_feature_noise_resume.ckpt"));
}

TEST(FeatureNoiseTest, TheSettingIsStoredAndBadValuesAreRefused) {
  EXPECT_EQ(TrainConfigFromJson(ToJson(NoiseConfig(0.25))).feature_noise, 0.25);
  nlohmann::json j = nlohmann::json::parse(ToJson(NoiseConfig(0.25)));
  j.erase("feature_noise");  // as written before the setting existed
  EXPECT_EQ(TrainConfigFromJson(j.dump()).feature_noise, 0.0);

  const Dataset images = testing::MakeImageTask(13, 8, 16);
  for (double bad : {-0.1, kMaxFeatureNoise + 1, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    try {
      Trainer trainer(images, testing::SmallImageNet(), NoiseConfig(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("feature_noise must be between 0 and 10"));
    }
  }
}

}  // namespace
}  // namespace recon::learn
