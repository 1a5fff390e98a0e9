// What the trainer refuses to start with, and the settings' names.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::MakeVectorTask;

// The message of the UserError that constructing a trainer throws ("" if none).
std::string ConstructionError(const Dataset& data, const NetworkConfig& network,
                              const TrainConfig& train) {
  try {
    Trainer trainer(data, network, train);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(SetupTest, RejectsFeatureSizeNotAboveBeaconSize) {
  Dataset data = MakeVectorTask(1, 2);
  data.spec.b_dim = 8;
  for (Episode& e : data.demos) {
    for (Sample& s : e.samples) s.b.assign(8, 0.5f);
  }
  NetworkConfig network;  // k = 6
  EXPECT_THAT(ConstructionError(data, network, TrainConfig{}),
              AllOf(HasSubstr("k=6"), HasSubstr("d=8"), HasSubstr("must exceed")));
  network.feature_dim = 8;  // k == d is not enough either
  EXPECT_THAT(ConstructionError(data, network, TrainConfig{}), HasSubstr("k=8"));
  network.feature_dim = 9;
  EXPECT_EQ(ConstructionError(data, network, TrainConfig{}), "");
  // The Baseline has no beacon net, so k <= d is fine for it.
  TrainConfig baseline;
  baseline.method = Method::kBaseline;
  network.feature_dim = 2;
  EXPECT_EQ(ConstructionError(data, network, baseline), "");
}

TEST(SetupTest, RejectsInvalidSettingsAndData) {
  const Dataset data = MakeVectorTask(1, 2);
  const NetworkConfig network;
  auto with = [](auto change) {
    TrainConfig t;
    change(t);
    return t;
  };
  EXPECT_THAT(ConstructionError(data, network, with([](TrainConfig& t) { t.steps = 0; })),
              HasSubstr("steps must be positive"));
  EXPECT_THAT(ConstructionError(data, network, with([](TrainConfig& t) { t.batch_size = -1; })),
              HasSubstr("batch_size must be positive"));
  for (const double rate : {0.0, 1e-300, -1e-3, static_cast<double>(NAN)}) {
    EXPECT_THAT(
        ConstructionError(data, network, with([rate](TrainConfig& t) { t.learning_rate = rate; })),
        HasSubstr("learning_rate must be at least 1e-09"))
        << rate;
  }
  EXPECT_THAT(ConstructionError(data, network, with([](TrainConfig& t) { t.beacon_weight = NAN; })),
              HasSubstr("beacon_weight"));

  Dataset nan_data = data;
  nan_data.demos[1].samples[2].y[3] = NAN;
  EXPECT_THAT(ConstructionError(nan_data, network, TrainConfig{}),
              AllOf(HasSubstr("demonstration 1"), HasSubstr("sample 2"), HasSubstr("'y'")));

  Dataset no_beacons = data;
  no_beacons.spec.b_dim = 0;
  for (Episode& e : no_beacons.demos) {
    for (Sample& s : e.samples) s.b.clear();
  }
  EXPECT_THAT(ConstructionError(no_beacons, network, TrainConfig{}),
              HasSubstr("RECON needs beacon readings"));

  Dataset tiny_images = testing::MakeImageTask(1, 4, 8);
  EXPECT_THAT(ConstructionError(tiny_images, NetworkConfig{}, TrainConfig{}),
              HasSubstr("too small"));
}

TEST(SetupTest, NamesRoundTripAndUnknownNamesAreRejected) {
  EXPECT_EQ(ParseMethod(ToString(Method::kRecon)), Method::kRecon);
  EXPECT_EQ(ParseMethod(ToString(Method::kBaseline)), Method::kBaseline);
  EXPECT_EQ(ParseLossKind(ToString(LossKind::kNll)), LossKind::kNll);
  EXPECT_EQ(ParseLossKind(ToString(LossKind::kMseSample)), LossKind::kMseSample);
  EXPECT_THROW(ParseMethod("RECON-P"), UserError);
  EXPECT_THROW(ParseLossKind("mse"), UserError);
  EXPECT_THROW(SetThreads(0), UserError);

  const TrainConfig authors = AuthorsRecipe();
  EXPECT_EQ(authors.loss, LossKind::kMseSample);
  EXPECT_EQ(authors.learning_rate, 4e-4);
  EXPECT_EQ(authors.batch_size, 20);
  EXPECT_EQ(authors.steps, 6001);
  EXPECT_EQ(authors.beacon_weight, 1.2);
  EXPECT_EQ(authors.play_weight, 1.2);
  EXPECT_TRUE(authors.restart_rule);
}

}  // namespace
}  // namespace recon::learn
