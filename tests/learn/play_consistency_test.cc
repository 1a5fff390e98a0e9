// RECON's play-consistency term (TrainConfig::play_consistency): its loss and gradient, the play
// pairs it draws, what training with it does to the features, and its settings.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/beacon_filter.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "engine/learn/play_consistency.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<float> RandomFeatures(int rows, int k, uint64_t seed) {
  Rng rng(seed);
  std::vector<float> phi(static_cast<size_t>(rows) * k);
  for (float& v : phi) v = static_cast<float>(rng.Normal());
  return phi;
}

TEST(PlayConsistencyTest, TheGradientMatchesFiniteDifferencesOfTheLoss) {
  const int batch = 7, k = 3;  // an odd row: in the spread, in no pair
  const float weight = 2.5f;
  std::vector<float> phi = RandomFeatures(batch, k, 11);
  std::vector<float> grad(phi.size()), scratch(phi.size());
  PlayConsistencyLoss(phi.data(), batch, k, weight, grad.data());
  for (size_t i = 0; i < phi.size(); ++i) {
    const float h = 1e-2f, kept = phi[i];
    phi[i] = kept + h;
    const double up = PlayConsistencyLoss(phi.data(), batch, k, weight, scratch.data());
    phi[i] = kept - h;
    const double down = PlayConsistencyLoss(phi.data(), batch, k, weight, scratch.data());
    phi[i] = kept;
    const double numeric = weight * (up - down) / (2 * h);
    EXPECT_NEAR(grad[i], numeric, 2e-3 + 2e-2 * std::abs(numeric)) << "feature value " << i;
  }
}

TEST(PlayConsistencyTest, FeaturesThatDifferOnlyBetweenPairsCostNothingAndScaleChangesNothing) {
  const int k = 2;
  // Pairs (rows 0-1, 2-3, 4-5) agree; the pairs differ from each other.
  const std::vector<float> agreeing = {1, 2, 1, 2, -3, 0, -3, 0, 5, 5, 5, 5};
  std::vector<float> grad(agreeing.size());
  EXPECT_EQ(PlayConsistencyLoss(agreeing.data(), 6, k, 1.0f, grad.data()), 0.0f);
  for (float g : grad) EXPECT_EQ(g, 0.0f);

  const std::vector<float> phi = RandomFeatures(10, 4, 12);
  std::vector<float> scaled = phi;
  for (float& v : scaled) v *= 30.0f;
  std::vector<float> g1(phi.size()), g2(phi.size());
  const float loss = PlayConsistencyLoss(phi.data(), 10, 4, 1.0f, g1.data());
  EXPECT_GT(loss, 0.1f);  // independent rows: about 1
  EXPECT_NEAR(PlayConsistencyLoss(scaled.data(), 10, 4, 1.0f, g2.data()), loss, 1e-4 * loss);
  // Scaling cannot lower it: the gradient has no component along the features themselves.
  double along = 0;
  for (size_t i = 0; i < phi.size(); ++i) along += g1[i] * phi[i];
  EXPECT_NEAR(along, 0.0, 1e-4);
}

TEST(PlayConsistencyTest, AOneRowBatchHasNoPairAndNoLoss) {
  const std::vector<float> phi = {1, 2, 3};
  std::vector<float> grad = {9, 9, 9};
  EXPECT_EQ(PlayConsistencyLoss(phi.data(), 1, 3, 1.0f, grad.data()), 0.0f);
  EXPECT_THAT(grad, ElementsAre(0, 0, 0));
}

TEST(PlayConsistencyTest, PartnersComeFromTheSameChunkAndAreNeverTheRowItself) {
  const PlayChunks chunks = PlayChunks::FromGroups(GroupsOfChunks(7, {3, 1, 3}));
  EXPECT_THAT(chunks.first, ElementsAre(0, 0, 0, 3, 4, 4, 4));
  EXPECT_THAT(chunks.size, ElementsAre(3, 3, 3, 1, 3, 3, 3));
  Rng rng(3);
  for (int64_t row = 0; row < 7; ++row) {
    std::set<int64_t> seen;
    for (int draw = 0; draw < 200; ++draw) seen.insert(chunks.Partner(row, rng));
    const int64_t first = chunks.first[row], size = chunks.size[row];
    if (size == 1) {
      EXPECT_THAT(seen, ElementsAre(row));
      continue;
    }
    EXPECT_EQ(seen.size(), static_cast<size_t>(size - 1)) << "row " << row;
    EXPECT_EQ(seen.count(row), 0u) << "row " << row;
    for (int64_t partner : seen) {
      EXPECT_GE(partner, first);
      EXPECT_LT(partner, first + size);
    }
  }
  // Play data whose chunks are unknown: each row is its own.
  EXPECT_THAT(PlayChunks::FromGroups(GroupsOfChunks(3, {})).size, ElementsAre(1, 1, 1));
}

// The vector task with play data in chunks of 6: within a chunk the beacon's object (y[0], y[1])
// stands still and the distractors (y[2..5]) move, as the bowl does during play.
Dataset ChunkedPlayTask(uint64_t seed) {
  Dataset data = testing::MakeVectorTask(seed, 12, 0);
  Rng rng(seed + 50);
  const int chunks = 8, per_chunk = 6;
  for (int c = 0; c < chunks; ++c) {
    const float tx = static_cast<float>(rng.Uniform(-1, 1)),
                ty = static_cast<float>(rng.Uniform(-1, 1));
    for (int i = 0; i < per_chunk; ++i) {
      PlaySample s;
      s.x = {0.0f, 0.0f};
      s.y = {tx, ty};
      for (int j = 0; j < 4; ++j) s.y.push_back(static_cast<float>(rng.Uniform(-1, 1)));
      s.b = {tx, ty};
      data.play.push_back(s);
    }
    data.play_chunks.push_back(per_chunk);
  }
  return data;
}

TrainConfig ConsistencyConfig(double weight) {
  TrainConfig train;
  train.steps = 400;
  train.seed = 8;
  train.play_consistency = weight;
  return train;
}

// The trained feature net's consistency loss over every play chunk's rows (each row paired with
// every other of its chunk).
double WithinChunkSpread(const Policy& policy, const Dataset& data) {
  std::vector<float> phi;
  int k = 0;
  std::vector<float> pairs;
  size_t first = 0;
  for (int size : data.play_chunks) {
    for (int a = 0; a < size; ++a) {
      for (int b = a + 1; b < size; ++b) {
        for (int row : {a, b}) {
          const PlaySample& s = data.play[first + row];
          const std::vector<float> f = policy.Features(s.x, s.y);
          k = static_cast<int>(f.size());
          pairs.insert(pairs.end(), f.begin(), f.end());
        }
      }
    }
    first += size;
  }
  const int rows = static_cast<int>(pairs.size()) / k;
  std::vector<float> grad(pairs.size());
  return PlayConsistencyLoss(pairs.data(), rows, k, 1.0f, grad.data());
}

TEST(PlayConsistencyTest, TrainingWithItMakesTheFeaturesBlindToWhatMovesWithinAChunk) {
  NetworkConfig network;
  network.feature_mlp_hidden = {32};
  for (uint64_t seed : {21, 24, 27}) {
    const Dataset data = ChunkedPlayTask(seed);
    auto train = [&](double weight) {
      Trainer trainer(data, network, ConsistencyConfig(weight));
      trainer.Train();
      return WithinChunkSpread(trainer.policy(), data);
    };
    // Without the term the k - d features the beacon net does not need follow the distractors.
    const double without = train(0), with = train(1);
    EXPECT_LT(with, 0.5 * without) << "data seed " << seed;
  }
}

TEST(PlayConsistencyTest, ItIsReproducibleAndLeavesTheBaselineAndRunsWithoutPlayAsTheyWere) {
  const Dataset data = ChunkedPlayTask(22);
  NetworkConfig network;
  network.feature_mlp_hidden = {16};
  auto probe = [&](const Dataset& d, Method method, double weight) {
    TrainConfig train = ConsistencyConfig(weight);
    train.steps = 30;
    train.method = method;
    Trainer trainer(d, network, train);
    trainer.Train();
    return testing::Probe(trainer.policy(), d);
  };
  const std::vector<float> recon = probe(data, Method::kRecon, 1);
  EXPECT_TRUE(testing::BitwiseEqual(recon, probe(data, Method::kRecon, 1)));
  EXPECT_FALSE(testing::BitwiseEqual(recon, probe(data, Method::kRecon, 0)));
  EXPECT_TRUE(
      testing::BitwiseEqual(probe(data, Method::kBaseline, 0), probe(data, Method::kBaseline, 5)));
  Dataset no_play = data;
  no_play.play.clear();
  no_play.play_chunks.clear();
  EXPECT_TRUE(
      testing::BitwiseEqual(probe(no_play, Method::kRecon, 0), probe(no_play, Method::kRecon, 5)));
}

TEST(PlayConsistencyTest, AResumedRunFinishesBitwiseAsTheUninterruptedOne) {
  // The pairs come from the batch stream, so a checkpoint must carry it mid-run.
  const Dataset data = ChunkedPlayTask(24);
  NetworkConfig network;
  network.feature_mlp_hidden = {16};
  TrainConfig train = ConsistencyConfig(1);
  train.steps = 60;
  EXPECT_TRUE(testing::ResumedRunMatchesUninterrupted(
      data, network, train, ::testing::TempDir() + "/play_consistency_resume.ckpt"));
}

TEST(PlayConsistencyTest, TheSettingIsStoredOldConfigsReadOffAndBadValuesAreRefused) {
  EXPECT_EQ(TrainConfigFromJson(ToJson(ConsistencyConfig(0.75))).play_consistency, 0.75);
  nlohmann::json j = nlohmann::json::parse(ToJson(ConsistencyConfig(0.75)));
  j.erase("play_consistency");  // as written before the setting existed
  EXPECT_EQ(TrainConfigFromJson(j.dump()).play_consistency, 0.0);

  const Dataset data = ChunkedPlayTask(23);
  for (double bad : {-0.5, kMaxPlayConsistency * 2, std::nan("")}) {
    try {
      Trainer trainer(data, NetworkConfig{}, ConsistencyConfig(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("play_consistency must be between 0 and 100"));
    }
  }
}

}  // namespace
}  // namespace recon::learn
