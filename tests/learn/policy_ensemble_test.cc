// A deep ensemble of policies (Policy::Ensemble): its actions, chunks and gates are the mean of
// its members', its features the first member's, and members that cannot act as one are refused.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::HasSubstr;

Policy Train(const Dataset& data, const NetworkConfig& network, uint64_t seed) {
  TrainConfig train;
  train.method = Method::kBaseline;
  train.steps = 30;
  train.seed = seed;
  Trainer trainer(data, network, train);
  trainer.Train();
  return trainer.policy();
}

NetworkConfig ChunkedNet(int chunk) {
  NetworkConfig network = testing::SmallImageNet();
  network.action_chunk = chunk;
  return network;
}

struct SampleRows {
  std::vector<std::vector<float>> xs, ys;
};

SampleRows FirstRows(const Dataset& data, int count) {
  SampleRows rows;
  for (const Episode& e : data.demos) {
    for (const Sample& s : e.samples) {
      if (static_cast<int>(rows.xs.size()) == count) return rows;
      rows.xs.push_back(s.x);
      rows.ys.push_back(s.y);
    }
  }
  return rows;
}

TEST(PolicyEnsembleTest, ActionsAndChunksAreTheMeanOfTheMembers) {
  const Dataset data = testing::MakeImageTask(31, 24, 16);
  const NetworkConfig network = ChunkedNet(3);
  const std::vector<Policy> members = {Train(data, network, 1), Train(data, network, 2),
                                       Train(data, network, 3)};
  const Policy ensemble = Policy::Ensemble(members);
  EXPECT_EQ(ensemble.ensemble_size(), 3);
  EXPECT_EQ(members[0].ensemble_size(), 1);
  EXPECT_EQ(ensemble.action_chunk(), 3);
  const SampleRows rows = FirstRows(data, 6);
  const auto chunks = ensemble.ActChunkBatch(rows.xs, rows.ys);
  const auto actions = ensemble.ActBatch(rows.xs, rows.ys);
  std::vector<std::vector<std::vector<float>>> member_chunks;
  for (const Policy& m : members) member_chunks.push_back(m.ActChunkBatch(rows.xs, rows.ys));
  ASSERT_EQ(chunks.size(), rows.xs.size());
  double spread = 0;  // how much the members disagree, so that a mean is a test
  for (size_t r = 0; r < chunks.size(); ++r) {
    ASSERT_EQ(chunks[r].size(), member_chunks[0][r].size());
    for (size_t j = 0; j < chunks[r].size(); ++j) {
      const double mean =
          (member_chunks[0][r][j] + member_chunks[1][r][j] + member_chunks[2][r][j]) / 3.0;
      EXPECT_NEAR(chunks[r][j], mean, 1e-5 * (1 + std::abs(mean))) << r << "," << j;
      spread += std::abs(member_chunks[0][r][j] - member_chunks[1][r][j]);
    }
    // The first action of the chunk is what ActBatch and Act give.
    for (size_t j = 0; j < actions[r].size(); ++j) EXPECT_EQ(actions[r][j], chunks[r][j]);
    EXPECT_EQ(ensemble.Act(rows.xs[r], rows.ys[r]), actions[r]);
  }
  EXPECT_GT(spread, 1e-3);
  // Features do not average across models: they are the first member's.
  EXPECT_EQ(ensemble.Features(rows.xs[0], rows.ys[0]), members[0].Features(rows.xs[0], rows.ys[0]));
}

TEST(PolicyEnsembleTest, AnEnsembleOfOneIsItsMemberAndEnsemblesNest) {
  const Dataset data = testing::MakeImageTask(32, 24, 16);
  const NetworkConfig network = ChunkedNet(1);
  const Policy a = Train(data, network, 4), b = Train(data, network, 5);
  EXPECT_TRUE(
      testing::BitwiseEqual(testing::Probe(Policy::Ensemble({a}), data), testing::Probe(a, data)));
  const Policy nested = Policy::Ensemble({Policy::Ensemble({a, b}), a});
  EXPECT_EQ(nested.ensemble_size(), 3);
  const SampleRows rows = FirstRows(data, 4);
  const auto got = nested.ActBatch(rows.xs, rows.ys);
  const auto pa = a.ActBatch(rows.xs, rows.ys), pb = b.ActBatch(rows.xs, rows.ys);
  for (size_t r = 0; r < got.size(); ++r) {
    for (size_t j = 0; j < got[r].size(); ++j) {
      const double mean = (2.0 * pa[r][j] + pb[r][j]) / 3.0;
      EXPECT_NEAR(got[r][j], mean, 1e-5 * (1 + std::abs(mean)));
    }
  }
}

TEST(PolicyEnsembleTest, MembersThatCannotActAsOneAreRefused) {
  try {
    Policy::Ensemble({});
    ADD_FAILURE() << "an empty ensemble";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("at least one member"));
  }
  const Dataset data = testing::MakeImageTask(33, 24, 16);
  const Policy single = Train(data, ChunkedNet(1), 6);
  const Policy chunked = Train(data, ChunkedNet(2), 7);
  try {
    Policy::Ensemble({single, chunked});
    ADD_FAILURE() << "members with different chunks";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("member 1 differs from the first"));
  }
  EXPECT_THROW(Policy::Ensemble({single, Policy()}), UserError);  // an empty member
}

}  // namespace
}  // namespace recon::learn
