// The feature gate's targets by disagreement (gate_targets.h): marked where another
// demonstration's teacher did something else at the nearest robot state, and only there.

#include "engine/learn/gate_targets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "engine/core/rng.h"

namespace recon::learn {
namespace {

// One episode of `steps` samples: x = (t, 7) with t = the step / 10 (the second dimension never
// varies), actions u(step).
Episode Ramp(int steps, const std::function<std::vector<float>(int)>& u) {
  Episode episode;
  for (int i = 0; i < steps; ++i) {
    Sample s;
    s.x = {0.1f * static_cast<float>(i), 7.0f};
    s.y = {0.0f};
    s.u = u(i);
    episode.samples.push_back(s);
  }
  return episode;
}

TrainingData Data(const std::vector<Episode>& episodes, int u_dim = 1, int chunk = 1) {
  Dataset data;
  data.spec = DataSpec{2, {1}, 0, u_dim};
  data.demos = episodes;
  return TrainingData::From(data, 1.0f, chunk);
}

// The variance of the rows' first action, dimension 0.
double Variance(const TrainingData& data) {
  double sum = 0, square = 0;
  const int width = data.spec.u_dim * data.action_chunk;
  for (int64_t r = 0; r < data.num_demo; ++r) {
    sum += data.demo_u[r * width];
    square += data.demo_u[r * width] * data.demo_u[r * width];
  }
  const double n = static_cast<double>(data.num_demo), mean = sum / n;
  return square / n - mean * mean;
}

TEST(GateTargetsTest, MarksTheStatesWhereAnotherDemonstrationActedOtherwise) {
  // Every teacher holds still for 6 steps, then moves to the plate's side: +1 in two
  // demonstrations, -1 in the third.
  auto side = [](float sign) {
    return Ramp(21, [sign](int i) { return std::vector<float>{i < 6 ? 0.0f : sign}; });
  };
  const TrainingData data = Data({side(1), side(1), side(-1)});
  ASSERT_EQ(data.demo_episode.size(), 63u);
  EXPECT_EQ(data.demo_episode[20], 0);
  EXPECT_EQ(data.demo_episode[21], 1);
  const double variance = Variance(data);
  const std::vector<float> d = DemonstrationDisagreement(data);
  for (int64_t r = 0; r < data.num_demo; ++r) {
    const int step = static_cast<int>(r % 21);
    if (step < 6) {
      EXPECT_FLOAT_EQ(d[r], 0.0f) << "row " << r << ": every teacher did the same";
    } else if (step <= 10) {
      // Within 5 steps of the other side's rows that still held still: (1 - 0)^2.
      EXPECT_NEAR(d[r], 1.0 / variance, 1e-5) << "row " << r;
    } else {
      EXPECT_NEAR(d[r], 4.0 / variance, 1e-5) << "row " << r << ": (1 - -1)^2";
    }
  }
  const std::vector<float> targets = DisagreementGateTargets(data, {}, 2.0 / variance);
  for (int64_t r = 0; r < data.num_demo; ++r) {
    EXPECT_EQ(targets[r], r % 21 > 10 ? 1.0f : 0.0f) << "row " << r;
  }
}

TEST(GateTargetsTest, TheSameActionAFewStepsLaterIsAgreement) {
  // The fingers close at step 8 in one demonstration and at `late` in the other.
  auto close_at = [](int step) {
    return Ramp(30, [step](int i) { return std::vector<float>{i < step ? 0.0f : 1.0f}; });
  };
  for (float d : DemonstrationDisagreement(Data({close_at(8), close_at(13)}))) {
    EXPECT_EQ(d, 0.0f) << "5 steps apart: the same close";
  }
  const std::vector<float> later = DemonstrationDisagreement(Data({close_at(8), close_at(16)}));
  EXPECT_GT(later[10], 0.0f) << "8 steps apart: the first had closed, the second had not";
  EXPECT_EQ(later[2], 0.0f);
  EXPECT_EQ(later[25], 0.0f);
}

TEST(GateTargetsTest, AChunkIsComparedPerAction) {
  auto constant = [](float value) {
    return Ramp(12, [value](int) { return std::vector<float>{value}; });
  };
  for (int chunk : {1, 4}) {
    // Variance 1 (half +1, half -1), difference (1 - -1)^2 = 4 per action at every row.
    for (float d : DemonstrationDisagreement(Data({constant(1), constant(-1)}, 1, chunk))) {
      EXPECT_FLOAT_EQ(d, 4.0f) << "chunk " << chunk;
    }
  }
}

TEST(GateTargetsTest, EachActionDimensionWeighsByItsSizeInTheUsersUnits) {
  // Two action dimensions: a joint that carries the arm (+-1) and one that hardly moves
  // (+-0.01). Demonstrations that differ only in the small one hardly disagree.
  auto episode = [](float big, float small) {
    return Ramp(10, [=](int) { return std::vector<float>{big, small}; });
  };
  const TrainingData raw = Data({episode(1, 0.01f), episode(1, -0.01f), episode(-1, 0.01f)}, 2);
  const std::vector<float> d = DemonstrationDisagreement(raw);
  // Total variance: 8/9 (the big dimension) + 0.0001 * 8/9 (the small one).
  const double total = 8.0 / 9.0 * (1 + 1e-4);
  EXPECT_NEAR(d[0], 4 / total, 1e-4) << "episode 0 meets episode 2: the big dimension only";
  EXPECT_NEAR(d[10], (4 + 0.0004) / total, 1e-4) << "episode 1 meets episode 2: both";
  // The same rows standardised per dimension, with their scales: the same disagreement.
  TrainingData standardised = raw;
  const std::vector<float> offset = {1.0f / 3, 0.01f / 3};
  const std::vector<float> scale = {static_cast<float>(std::sqrt(8.0 / 9)),
                                    static_cast<float>(0.01 * std::sqrt(8.0 / 9))};
  for (size_t i = 0; i < standardised.demo_u.size(); ++i) {
    standardised.demo_u[i] = (standardised.demo_u[i] - offset[i % 2]) / scale[i % 2];
  }
  const std::vector<float> scaled = DemonstrationDisagreement(standardised, scale);
  for (size_t r = 0; r < d.size(); ++r) EXPECT_NEAR(scaled[r], d[r], 1e-3) << "row " << r;
  // Demonstrations that differ in the small dimension alone hardly disagree; standardised
  // without their scales, they would disagree as much as random rows.
  auto swinging = [](float small) {  // the big joint swings the same way in both
    return Ramp(10, [=](int i) { return std::vector<float>{i < 5 ? 1.0f : -1.0f, small}; });
  };
  TrainingData small_only = Data({swinging(0.01f), swinging(-0.01f)}, 2);
  EXPECT_LT(DemonstrationDisagreement(small_only)[0], 0.001f);
  for (size_t i = 1; i < small_only.demo_u.size(); i += 2) small_only.demo_u[i] *= 100.0f;
  EXPECT_GT(DemonstrationDisagreement(small_only)[0], 1.0f);
}

TEST(GateTargetsTest, ADisagreementShorterThanTwoChunksIsNotMarked) {
  // Two demonstrations alike but for a 3-step burst at steps 10-12 in one and a 12-step stretch
  // from step 30 in the other.
  auto episode = [](int from, int length) {
    return Ramp(60, [=](int i) {
      return std::vector<float>{i >= from && i < from + length ? 5.0f : 0.0f};
    });
  };
  for (int chunk : {1, 4}) {
    const TrainingData data = Data({episode(10, 3), episode(30, 12)}, 1, chunk);
    const std::vector<float> d = DemonstrationDisagreement(data);
    const std::vector<float> targets = DisagreementGateTargets(data, {}, 0.1);
    int marked_burst = 0, marked_stretch = 0;
    for (int64_t r = 0; r < 60; ++r) {
      if (r >= 5 && r < 15) marked_burst += targets[r] > 0;
      marked_stretch += targets[60 + r] > 0;  // the second demonstration's rows
    }
    EXPECT_GT(d[11], 0.1f) << "chunk " << chunk << ": the burst does disagree";
    if (chunk == 1) {
      EXPECT_GT(marked_burst, 0) << "with chunks of 1 every run counts";
    } else {
      EXPECT_EQ(marked_burst, 0) << "3 actions mark 6 rows, fewer than two chunks of 4: timing";
    }
    EXPECT_GE(marked_stretch, 12) << "chunk " << chunk << ": the long stretch stays";
  }
}

TEST(GateTargetsTest, ASingleDemonstrationDisagreesWithNothing) {
  const TrainingData data =
      Data({Ramp(11, [](int i) { return std::vector<float>{static_cast<float>(i % 3)}; })});
  for (float d : DemonstrationDisagreement(data)) EXPECT_EQ(d, 0.0f);
}

TEST(GateTargetsTest, TheNearestStateDoesNotDependOnEachDimensionsUnits) {
  // Random states and actions; the same data with its first state dimension in other units
  // (x 1000) must pair the same rows. A raw Euclidean distance would let that dimension decide.
  auto make = [](float scale) {
    Rng rng(5);
    Dataset data;
    data.spec = DataSpec{3, {1}, 0, 1};
    for (int e = 0; e < 3; ++e) {
      Episode episode;
      for (int i = 0; i < 30; ++i) {
        Sample s;
        s.x = {scale * static_cast<float>(rng.Uniform(-1, 1)),
               static_cast<float>(rng.Uniform(-1, 1)), 7.0f};
        s.y = {0.0f};
        s.u = {static_cast<float>(rng.Uniform(-1, 1))};
        episode.samples.push_back(s);
      }
      data.demos.push_back(episode);
    }
    return TrainingData::From(data, 1.0f, 1);
  };
  const std::vector<float> plain = DemonstrationDisagreement(make(1.0f));
  const std::vector<float> scaled = DemonstrationDisagreement(make(1000.0f));
  ASSERT_EQ(plain.size(), scaled.size());
  int positive = 0;
  for (size_t r = 0; r < plain.size(); ++r) {
    EXPECT_FLOAT_EQ(plain[r], scaled[r]) << "row " << r;
    positive += plain[r] > 0;
  }
  EXPECT_GT(positive, 80) << "random teachers disagree almost everywhere";
}

}  // namespace
}  // namespace recon::learn
