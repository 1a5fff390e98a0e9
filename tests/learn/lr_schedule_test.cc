// The learning-rate schedule (TrainConfig::lr_schedule): its values, that the trainer follows
// it, that checkpoints keep it, and that old checkpoints read as constant.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "engine/core/error.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using testing::BitwiseEqual;
using ::testing::HasSubstr;
using testing::MakeVectorTask;
using testing::Probe;

TEST(LrScheduleTest, CosineStartsAtTheRateHalvesAtTheMiddleAndEndsNearZero) {
  const double lr = 1e-3;
  const int steps = 1000;
  EXPECT_DOUBLE_EQ(ScheduledLearningRate(lr, LrSchedule::kCosine, 0, steps), lr);
  EXPECT_NEAR(ScheduledLearningRate(lr, LrSchedule::kCosine, 500, steps), lr / 2, 1e-15);
  const double last = ScheduledLearningRate(lr, LrSchedule::kCosine, steps - 1, steps);
  EXPECT_GT(last, 0.0) << "the last step still moves the weights";
  EXPECT_LT(last, lr * 1e-5);
  double previous = lr;
  for (int step = 1; step < steps; ++step) {
    const double now = ScheduledLearningRate(lr, LrSchedule::kCosine, step, steps);
    EXPECT_LT(now, previous) << "step " << step;
    previous = now;
  }
  for (int step : {0, 500, 999}) {
    EXPECT_EQ(ScheduledLearningRate(lr, LrSchedule::kConstant, step, steps), lr);
  }
}

TEST(LrScheduleTest, TheTrainerFollowsItAndACheckpointKeepsIt) {
  const Dataset data = MakeVectorTask(5, 20, 3);
  TrainConfig constant = AuthorsRecipe();
  constant.steps = 40;
  constant.restart_rule = false;
  TrainConfig cosine = constant;
  cosine.lr_schedule = LrSchedule::kCosine;
  NetworkConfig network;
  Trainer a(data, network, constant), b(data, network, cosine);
  a.Train();
  b.Train();
  EXPECT_FALSE(BitwiseEqual(Probe(a.policy(), data), Probe(b.policy(), data)))
      << "the schedule changes the run";
  // Resumed halfway, a cosine run continues its schedule where it was (same weights as
  // straight through).
  const std::string path =
      (std::filesystem::path(::testing::TempDir()) / "recon_lr_schedule_half.ckpt").string();
  Trainer half(data, network, cosine);
  std::atomic<bool> cancel{false};
  half.SetObserver([&](const StepMetrics& m) { cancel = m.step + 1 == 20; });
  ASSERT_TRUE(half.Train(&cancel).cancelled);
  half.SaveCheckpoint(path);
  const std::unique_ptr<Trainer> resumed = Trainer::Resume(path, data);
  EXPECT_EQ(resumed->train_config().lr_schedule, LrSchedule::kCosine);
  resumed->Train();
  EXPECT_TRUE(BitwiseEqual(Probe(resumed->policy(), data), Probe(b.policy(), data)));
  std::filesystem::remove(path);
}

TEST(LrScheduleTest, OldConfigsReadAsConstantAndUnknownNamesAreErrors) {
  std::string old = ToJson(TrainConfig{});
  const std::string field = ",\"lr_schedule\":\"constant\"";
  const size_t at = old.find(field);
  ASSERT_NE(at, std::string::npos) << old;
  old.erase(at, field.size());
  EXPECT_EQ(TrainConfigFromJson(old).lr_schedule, LrSchedule::kConstant);
  TrainConfig cosine;
  cosine.lr_schedule = LrSchedule::kCosine;
  EXPECT_EQ(TrainConfigFromJson(ToJson(cosine)).lr_schedule, LrSchedule::kCosine);
  EXPECT_EQ(ParseLrSchedule("cosine"), LrSchedule::kCosine);
  try {
    ParseLrSchedule("linear");
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown learning-rate schedule 'linear'"));
  }
}

}  // namespace
}  // namespace recon::learn
