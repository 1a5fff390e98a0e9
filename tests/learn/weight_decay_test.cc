// Decoupled weight decay (TrainConfig::weight_decay): which parameters decay, by how much per
// step, that it leaves Adam's own update alone, and that the setting is stored and checked.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "engine/core/error.h"
#include "engine/learn/architecture.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "engine/learn/trainer_impl.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::HasSubstr;

TrainConfig DecayConfig(double weight_decay, Method method = Method::kRecon) {
  TrainConfig train;
  train.method = method;
  train.steps = 40;
  train.seed = 3;
  train.learning_rate = 1e-3;
  train.weight_decay = weight_decay;
  return train;
}

NetworkConfig KeypointNet() {
  NetworkConfig network = testing::SmallImageNet();
  network.spatial_softmax = true;
  return network;
}

// Which parameter is a weight, from the layer plan alone: 1 for weights, 0 for everything else.
std::vector<int> WeightMask(const Architecture& arch) {
  std::vector<int> mask(static_cast<size_t>(arch.num_params), 0);
  for (const ParamRange& r : WeightRanges(arch)) {
    for (int64_t i = r.offset; i < r.offset + r.size; ++i) ++mask[static_cast<size_t>(i)];
  }
  return mask;
}

TEST(WeightDecayTest, TheRangesAreEveryWeightOnceAndNoBiasOrTemperature) {
  for (const NetworkConfig& network : {testing::SmallImageNet(), KeypointNet()}) {
    const Architecture arch =
        BuildArchitecture(testing::MakeImageTask(4, 8, 16).spec, network, Method::kRecon);
    const std::vector<int> mask = WeightMask(arch);
    int64_t expected = 0;
    for (const ConvLayer& c : arch.convs) {
      expected += static_cast<int64_t>(c.out_channels) * c.in_channels * c.kernel * c.kernel;
      for (int i = 0; i < c.out_channels; ++i) EXPECT_EQ(mask[c.bias + i], 0);
    }
    for (const auto* mlp : {&arch.feature, &arch.policy, &arch.beacon}) {
      ASSERT_FALSE(mlp->empty());
      for (const LinearLayer& l : *mlp) {
        expected += static_cast<int64_t>(l.in) * l.out;
        for (int i = 0; i < l.out; ++i) EXPECT_EQ(mask[l.bias + i], 0);
      }
    }
    if (arch.spatial_softmax) {
      EXPECT_EQ(mask[arch.keypoints.log_temperature], 0);
    }
    int64_t covered = 0;
    for (int m : mask) {
      EXPECT_LE(m, 1);  // no weight twice
      covered += m;
    }
    EXPECT_EQ(covered, expected);
  }
}

TEST(WeightDecayTest, OneStepShrinksEachWeightByTheRateTimesTheDecayAndNothingElse) {
  const Dataset data = testing::MakeImageTask(7, 24, 16, 6);
  constexpr double kDecay = 2.0;
  TrainerImpl plain(data, KeypointNet(), DecayConfig(0.0));
  TrainerImpl decayed(data, KeypointNet(), DecayConfig(kDecay));
  const std::vector<float> before = plain.State().params;
  ASSERT_EQ(before, decayed.State().params);  // the same initial weights
  plain.Step();
  decayed.Step();
  const TrainerState a = plain.State();
  const TrainerState b = decayed.State();
  // The gradient is taken before the decay, so both runs make the same Adam update; the decayed
  // one also loses lr * decay of each weight's value before the step.
  EXPECT_EQ(a.exp_avg, b.exp_avg);
  EXPECT_EQ(a.exp_avg_sq, b.exp_avg_sq);
  const std::vector<int> mask =
      WeightMask(BuildArchitecture(data.spec, KeypointNet(), Method::kRecon));
  const double shrink = 1e-3 * kDecay;
  int weights = 0;
  for (size_t i = 0; i < before.size(); ++i) {
    if (mask[i] == 0) {
      EXPECT_EQ(a.params[i], b.params[i]) << "parameter " << i << " is not a weight";
      continue;
    }
    ++weights;
    const double expected = static_cast<double>(a.params[i]) - shrink * before[i];
    EXPECT_NEAR(b.params[i], expected, 1e-7 + 1e-6 * std::abs(expected)) << "weight " << i;
  }
  EXPECT_GT(weights, 1000);
}

TEST(WeightDecayTest, TrainingWithDecayIsReproducibleAndSmallerThanWithout) {
  const Dataset data = testing::MakeImageTask(8, 24, 16, 6);
  auto norm_and_probe = [&](double decay) {
    Trainer trainer(data, testing::SmallImageNet(), DecayConfig(decay, Method::kBaseline));
    trainer.Train();
    return testing::Probe(trainer.policy(), data);
  };
  const std::vector<float> decayed = norm_and_probe(5.0);
  EXPECT_TRUE(testing::BitwiseEqual(decayed, norm_and_probe(5.0)));
  EXPECT_FALSE(testing::BitwiseEqual(decayed, norm_and_probe(0.0)));

  // Over a run the weights' norm falls with the decay: with no data term it would be exactly
  // prod(1 - lr_t * decay); with one it is still below the undecayed run's.
  auto weight_norm = [&](double decay) {
    TrainerImpl trainer(data, testing::SmallImageNet(), DecayConfig(decay, Method::kBaseline));
    for (int i = 0; i < 40; ++i) trainer.Step();
    const std::vector<float> params = trainer.State().params;
    double sum = 0;
    for (const ParamRange& r : WeightRanges(trainer.arch())) {
      for (int64_t i = r.offset; i < r.offset + r.size; ++i) sum += params[i] * params[i];
    }
    return std::sqrt(sum);
  };
  EXPECT_LT(weight_norm(10.0), weight_norm(0.0));
}

TEST(WeightDecayTest, TheDecayIsStoredAndBadValuesAreRefused) {
  EXPECT_EQ(TrainConfigFromJson(ToJson(DecayConfig(0.25))).weight_decay, 0.25);
  nlohmann::json j = nlohmann::json::parse(ToJson(DecayConfig(0.25)));
  j.erase("weight_decay");  // as written before the setting existed
  EXPECT_EQ(TrainConfigFromJson(j.dump()).weight_decay, 0.0);

  const Dataset data = testing::MakeVectorTask(5, 4);
  for (double bad : {-0.1, kMaxWeightDecay * 1.01, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    try {
      Trainer trainer(data, NetworkConfig{}, DecayConfig(bad));
      ADD_FAILURE() << "accepted " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("weight_decay must be between 0 and 10"));
    }
  }
}

}  // namespace
}  // namespace recon::learn
