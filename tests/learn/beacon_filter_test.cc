// Beacon readings smoothed before training (TrainConfig::beacon_filter_samples): the window, the
// episode and play-chunk boundaries it must not cross, and what training with it changes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/beacon_filter.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::ElementsAre;
using ::testing::FloatEq;
using ::testing::HasSubstr;

TEST(BeaconFilterTest, EachRowBecomesTheMeanOfItsWindowWithinItsGroup) {
  // Two values per row; rows 0-3 are one episode, rows 4-5 another.
  std::vector<float> b = {0, 10, 4, 10, 8, 10, 0, 50, 100, -1, 200, -3};
  SmoothBeaconRows(b, 2, {0, 0, 0, 0, 1, 1}, 1);
  EXPECT_THAT(b, ElementsAre(FloatEq(2), FloatEq(10),         // rows 0-1
                             FloatEq(4), FloatEq(10),         // rows 0-2
                             FloatEq(4), FloatEq(70.0f / 3),  // rows 1-3
                             FloatEq(4), FloatEq(30),         // rows 2-3
                             FloatEq(150), FloatEq(-2),       // rows 4-5, never 3
                             FloatEq(150), FloatEq(-2)));
}

TEST(BeaconFilterTest, ZeroLeavesTheReadingsAndALongWindowAveragesTheWholeGroup) {
  const std::vector<float> raw = {1, 2, 3, 4, 5};
  std::vector<float> b = raw;
  SmoothBeaconRows(b, 1, {0, 0, 0, 1, 1}, 0);
  EXPECT_EQ(b, raw);
  SmoothBeaconRows(b, 1, {0, 0, 0, 1, 1}, 1000);
  EXPECT_THAT(b, ElementsAre(FloatEq(2), FloatEq(2), FloatEq(2), FloatEq(4.5f), FloatEq(4.5f)));
}

TEST(BeaconFilterTest, PlayChunksGroupTheirRowsAndUnknownChunksKeepEveryRowAlone) {
  EXPECT_THAT(GroupsOfChunks(5, {2, 3}), ElementsAre(0, 0, 1, 1, 1));
  EXPECT_THAT(GroupsOfChunks(3, {}), ElementsAre(0, 1, 2));
}

Dataset NoisyBeaconTask(uint64_t seed) {
  // The vector task with each demonstration's beacon reading standing still and noisy, as a
  // plate's beacon does: only the filter makes its targets the same within an episode.
  Dataset data = testing::MakeVectorTask(seed, 6, 8);
  Rng noise(seed + 100);
  for (Episode& episode : data.demos) {
    for (Sample& s : episode.samples) {
      s.b = episode.samples.front().y;
      s.b.resize(2);
      for (float& v : s.b) v += static_cast<float>(0.3 * noise.Normal());
    }
  }
  data.play_chunks = {4, 4};
  return data;
}

TrainConfig FilterConfig(int samples) {
  TrainConfig train;
  train.steps = 40;
  train.seed = 5;
  train.beacon_filter_samples = samples;
  return train;
}

TEST(BeaconFilterTest, TrainingWithTheFilterIsReproducibleAndDiffersFromRawReadings) {
  const Dataset data = NoisyBeaconTask(3);
  NetworkConfig network;
  network.feature_mlp_hidden = {16};
  auto run = [&](int samples) {
    Trainer trainer(data, network, FilterConfig(samples));
    trainer.Train();
    return testing::Probe(trainer.policy(), data);
  };
  const std::vector<float> filtered = run(3);
  EXPECT_TRUE(testing::BitwiseEqual(filtered, run(3)));
  EXPECT_FALSE(testing::BitwiseEqual(filtered, run(0)));
  // The Baseline reads no beacon: the filter cannot change it.
  auto baseline = [&](int samples) {
    TrainConfig train = FilterConfig(samples);
    train.method = Method::kBaseline;
    Trainer trainer(data, network, train);
    trainer.Train();
    return testing::Probe(trainer.policy(), data);
  };
  EXPECT_TRUE(testing::BitwiseEqual(baseline(0), baseline(1000)));
}

TEST(BeaconFilterTest, TheSettingIsStoredOldConfigsReadRawAndBadValuesAreRefused) {
  EXPECT_EQ(TrainConfigFromJson(ToJson(FilterConfig(25))).beacon_filter_samples, 25);
  nlohmann::json j = nlohmann::json::parse(ToJson(FilterConfig(25)));
  j.erase("beacon_filter_samples");  // as written before the setting existed
  EXPECT_EQ(TrainConfigFromJson(j.dump()).beacon_filter_samples, 0);

  const Dataset data = NoisyBeaconTask(4);
  for (int bad : {-1, kMaxBeaconFilterSamples + 1}) {
    try {
      Trainer trainer(data, NetworkConfig{}, FilterConfig(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("beacon_filter_samples must be between 0 and 100000"));
    }
  }
}

TEST(BeaconFilterTest, PlayChunksThatDoNotAddUpToThePlayDataAreRefused) {
  Dataset data = NoisyBeaconTask(5);
  data.play_chunks = {4, 5};
  try {
    Trainer trainer(data, NetworkConfig{}, FilterConfig(2));
    ADD_FAILURE() << "accepted chunks of 9 samples for 8";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the play chunks hold 9 samples, but there are 8"));
  }
}

}  // namespace
}  // namespace recon::learn
