// Checkpoints: exact round trips, exact resumption, and clear errors for files that do not fit.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <torch/torch.h>
#include <cmath>
#include <limits>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/learn/architecture.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "tests/learn/test_data.h"
#include "tests/support/user_error_of.h"

namespace recon::learn {
namespace {

using testing::BitwiseEqual;
using ::testing::HasSubstr;
using testing::MakeImageTask;
using testing::MakeVectorTask;
using testing::Probe;
using testing::SmallImageNet;
using recon::testing::UserErrorOf;

std::string TempPath(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / ("recon_learn_" + name)).string();
}

TrainConfig ShortAuthors(int steps) {
  TrainConfig t = AuthorsRecipe();
  t.steps = steps;
  t.restart_rule = false;
  return t;
}

torch::Tensor ReadTensor(const std::string& path, const std::string& key) {
  torch::serialize::InputArchive archive;
  archive.load_from(path);
  torch::Tensor t;
  archive.read(key, t);
  return t;
}

std::string ReadCheckpointString(const std::string& path, const std::string& key) {
  torch::serialize::InputArchive archive;
  archive.load_from(path);
  c10::IValue value;
  if (!archive.try_read(key, value)) return "";
  return value.toStringRef();
}

TEST(CheckpointTest, RoundTripGivesTheSamePolicy) {
  const Dataset data = MakeImageTask(3, 24, 16, 6);
  Trainer trainer(data, SmallImageNet(), ShortAuthors(30));
  trainer.Train();
  const std::string path = TempPath("roundtrip.ckpt");
  trainer.SaveCheckpoint(path);
  EXPECT_FALSE(std::filesystem::exists(TemporarySibling(path)));
  const Policy loaded = LoadPolicy(path);
  EXPECT_EQ(loaded.spec(), data.spec);
  EXPECT_TRUE(BitwiseEqual(Probe(loaded, data), Probe(trainer.policy(), data)));
  const Sample& s = data.demos[0].samples[3];
  EXPECT_TRUE(
      BitwiseEqual(loaded.PredictBeacon(s.x, s.y), trainer.policy().PredictBeacon(s.x, s.y)));

  const std::unique_ptr<Trainer> resumed = Trainer::Resume(path, data);
  EXPECT_EQ(resumed->step(), 30);
  EXPECT_EQ(resumed->network_config(), SmallImageNet());
  EXPECT_EQ(resumed->train_config(), ShortAuthors(30));
  EXPECT_TRUE(BitwiseEqual(Probe(resumed->policy(), data), Probe(trainer.policy(), data)));
}

// The studio trains its methods side by side, so two trainers save (and the rollouts load)
// checkpoints at the same moment; the first of them also loads the Torch module. Each thread
// writes and reads its own file many times over; every read must give back what was written.
TEST(CheckpointTest, CheckpointsAreWrittenAndReadFromSeveralThreadsAtOnce) {
  const Dataset data = MakeImageTask(3, 24, 16, 6);
  Trainer trainer(data, SmallImageNet(), ShortAuthors(5));
  trainer.Train();
  const std::vector<float> expected = Probe(trainer.policy(), data);
  constexpr int kThreads = 4, kRounds = 25;
  std::vector<int> matches(kThreads, 0);
  std::vector<std::string> errors(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const std::string path = TempPath("threads_" + std::to_string(t) + ".ckpt");
      try {
        for (int round = 0; round < kRounds; ++round) {
          trainer.SaveCheckpoint(path);
          matches[t] += BitwiseEqual(Probe(LoadPolicy(path), data), expected) ? 1 : 0;
        }
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) {
    EXPECT_EQ(errors[t], "") << "thread " << t;
    EXPECT_EQ(matches[t], kRounds) << "thread " << t;
  }
}

TEST(CheckpointTest, ResumeContinuesExactly) {
  // Image model with play data and sampling noise: every piece of state matters.
  const Dataset data = MakeImageTask(4, 24, 16, 6);
  const int steps = 40;
  Trainer straight(data, SmallImageNet(), ShortAuthors(steps));
  straight.Train();
  const std::string straight_path = TempPath("straight.ckpt");
  straight.SaveCheckpoint(straight_path);

  Trainer first_half(data, SmallImageNet(), ShortAuthors(steps));
  std::atomic<bool> cancel{false};
  first_half.SetObserver([&](const StepMetrics& m) { cancel = m.step + 1 == steps / 2; });
  ASSERT_TRUE(first_half.Train(&cancel).cancelled);
  ASSERT_EQ(first_half.step(), steps / 2);
  const std::string half_path = TempPath("half.ckpt");
  first_half.SaveCheckpoint(half_path);

  const std::unique_ptr<Trainer> resumed = Trainer::Resume(half_path, data);
  EXPECT_EQ(resumed->step(), steps / 2);
  const TrainResult result = resumed->Train();
  EXPECT_EQ(result.steps_run, steps);
  const std::string resumed_path = TempPath("resumed.ckpt");
  resumed->SaveCheckpoint(resumed_path);
  for (const char* key : {"params", "target_scaling", "exp_avg", "exp_avg_sq"}) {
    EXPECT_TRUE(torch::equal(ReadTensor(straight_path, key), ReadTensor(resumed_path, key))) << key;
  }
  EXPECT_TRUE(BitwiseEqual(Probe(resumed->policy(), data), Probe(straight.policy(), data)));
}

TEST(CheckpointTest, SpatialSoftmaxModelSavesLoadsAndResumesExactly) {
  const Dataset data = MakeImageTask(8, 24, 16, 6);
  NetworkConfig network = SmallImageNet();
  network.conv_channels = {4};  // 7x7 planes
  network.spatial_softmax = true;
  const int steps = 30;
  Trainer straight(data, network, ShortAuthors(steps));
  straight.Train();
  const std::string path = TempPath("keypoints.ckpt");
  straight.SaveCheckpoint(path);
  EXPECT_TRUE(NetworkConfigFromJson(ReadCheckpointString(path, "network")).spatial_softmax);
  const Policy loaded = LoadPolicy(path);
  EXPECT_TRUE(BitwiseEqual(Probe(loaded, data), Probe(straight.policy(), data)));

  Trainer first_half(data, network, ShortAuthors(steps));
  std::atomic<bool> cancel{false};
  first_half.SetObserver([&](const StepMetrics& m) { cancel = m.step + 1 == steps / 2; });
  ASSERT_TRUE(first_half.Train(&cancel).cancelled);
  const std::string half_path = TempPath("keypoints_half.ckpt");
  first_half.SaveCheckpoint(half_path);
  const std::unique_ptr<Trainer> resumed = Trainer::Resume(half_path, data);
  EXPECT_EQ(resumed->network_config(), network);
  resumed->Train();
  const std::string resumed_path = TempPath("keypoints_resumed.ckpt");
  resumed->SaveCheckpoint(resumed_path);
  for (const char* key : {"params", "exp_avg", "exp_avg_sq"}) {
    EXPECT_TRUE(torch::equal(ReadTensor(path, key), ReadTensor(resumed_path, key))) << key;
  }
  // The temperature is a trained weight like any other: it moved from log T = 0.
  const torch::Tensor params = ReadTensor(path, "params");
  const Architecture arch = BuildArchitecture(data.spec, network, Method::kRecon);
  EXPECT_NE(params[arch.keypoints.log_temperature].item<float>(), 0.0f);

  // The same file read as a network without the layer does not fit its weights.
  torch::serialize::InputArchive in;
  in.load_from(path);
  torch::serialize::OutputArchive out;
  for (const char* key : {"format", "train", "spec", "state"}) {
    c10::IValue value;
    ASSERT_TRUE(in.try_read(key, value));
    out.write(key, value);
  }
  NetworkConfig without = network;
  without.spatial_softmax = false;
  out.write("network", c10::IValue(ToJson(without)));
  for (const char* key : {"params", "target_scaling", "exp_avg", "exp_avg_sq"}) {
    torch::Tensor t;
    in.read(key, t);
    out.write(key, t);
  }
  const std::string bad = TempPath("keypoints_off.ckpt");
  out.save_to(bad);
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(bad); }), HasSubstr("architecture differs"));
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(bad, data); }), HasSubstr("architecture differs"));
}

TEST(CheckpointTest, FeatureGateModelSavesLoadsAndResumesExactly) {
  for (GateTarget target : {GateTarget::kLoss, GateTarget::kDisagreement}) {
    SCOPED_TRACE(ToString(target));
    const Dataset data = MakeImageTask(9, 24, 16, 6);
    NetworkConfig network = SmallImageNet();
    network.feature_gate_hidden = {6};
    TrainConfig train = ShortAuthors(30);
    train.gate_margin = 0.5;
    train.gate_target = target;
    Trainer straight(data, network, train);
    straight.Train();
    const std::string path = TempPath("gate.ckpt");
    straight.SaveCheckpoint(path);
    EXPECT_EQ(NetworkConfigFromJson(ReadCheckpointString(path, "network")).feature_gate_hidden,
              std::vector<int>{6});
    const TrainConfig stored = TrainConfigFromJson(ReadCheckpointString(path, "train"));
    EXPECT_DOUBLE_EQ(stored.gate_margin, 0.5);
    EXPECT_EQ(stored.gate_target, target);
    EXPECT_TRUE(BitwiseEqual(Probe(LoadPolicy(path), data), Probe(straight.policy(), data)));

    Trainer first_half(data, network, train);
    std::atomic<bool> cancel{false};
    first_half.SetObserver([&](const StepMetrics& m) { cancel = m.step + 1 == 15; });
    ASSERT_TRUE(first_half.Train(&cancel).cancelled);
    const std::string half_path = TempPath("gate_half.ckpt");
    first_half.SaveCheckpoint(half_path);
    const std::unique_ptr<Trainer> resumed = Trainer::Resume(half_path, data);
    resumed->Train();
    const std::string resumed_path = TempPath("gate_resumed.ckpt");
    resumed->SaveCheckpoint(resumed_path);
    for (const char* key : {"params", "exp_avg", "exp_avg_sq"}) {
      EXPECT_TRUE(torch::equal(ReadTensor(path, key), ReadTensor(resumed_path, key))) << key;
    }
    // The gate trained: its output bias moved from where it starts.
    const Architecture arch = BuildArchitecture(data.spec, network, Method::kRecon);
    EXPECT_NE(ReadTensor(path, "params")[arch.gate.back().bias].item<float>(), kGateInitialBias);
  }
  // A checkpoint from before the choice existed gated by the loss.
  std::string old = ToJson(TrainConfig{});
  const size_t at = old.find(",\"gate_target\":\"loss\"");
  ASSERT_NE(at, std::string::npos) << old;
  old.erase(at, std::string(",\"gate_target\":\"loss\"").size());
  EXPECT_EQ(TrainConfigFromJson(old).gate_target, GateTarget::kLoss);
  std::string bad = ToJson(TrainConfig{});
  bad.replace(bad.find("\"gate_target\":\"loss\""), 20, "\"gate_target\":\"vote\"");
  EXPECT_THAT(UserErrorOf([&] { TrainConfigFromJson(bad); }),
              HasSubstr("unknown gate target 'vote' (expected loss or disagreement)"));
}

TEST(CheckpointTest, ResumeRejectsOtherData) {
  const Dataset data = MakeVectorTask(1, 5);
  Trainer trainer(data, NetworkConfig{}, ShortAuthors(5));
  trainer.Train();
  const std::string path = TempPath("data.ckpt");
  trainer.SaveCheckpoint(path);

  Dataset changed = data;
  changed.demos[2].samples[1].u[0] += 0.25f;
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(path, changed); }), HasSubstr("fingerprint"));
  const Dataset other_shape = MakeImageTask(1, 4, 16);
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(path, other_shape); }),
              HasSubstr("trained on data shaped"));
  EXPECT_EQ(UserErrorOf([&] { Trainer::Resume(path, data); }), "");
}

TEST(CheckpointTest, MissingCorruptOrTruncatedFilesAreUserErrors) {
  const Dataset data = MakeVectorTask(1, 5);
  Trainer trainer(data, NetworkConfig{}, ShortAuthors(5));
  const std::string good = TempPath("good.ckpt");
  trainer.SaveCheckpoint(good);

  const std::string missing = TempPath("missing.ckpt");
  std::filesystem::remove(missing);
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(missing); }), HasSubstr("does not exist"));
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(missing, data); }), HasSubstr("does not exist"));

  const std::string garbage = TempPath("garbage.ckpt");
  std::ofstream(garbage) << "this is not a checkpoint";
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(garbage); }), HasSubstr("corrupt"));

  const std::string truncated = TempPath("truncated.ckpt");
  std::filesystem::copy_file(good, truncated, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::resize_file(truncated, std::filesystem::file_size(good) / 2);
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(truncated, data); }), HasSubstr(truncated));
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(truncated); }), HasSubstr(truncated));

  // A valid PyTorch archive that is not ours.
  const std::string foreign = TempPath("foreign.ckpt");
  torch::serialize::OutputArchive archive;
  archive.write("weights", torch::ones({3}));
  archive.save_to(foreign);
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(foreign); }), HasSubstr("missing"));

  EXPECT_THAT(UserErrorOf([&] { trainer.SaveCheckpoint(TempPath("no/such/dir.ckpt")); }),
              HasSubstr("cannot write checkpoint"));
}

// A copy of checkpoint `from` with `edit` applied to its entries (every other entry as it was).
void RewriteCheckpoint(const std::string& from, const std::string& to,
                       const std::function<void(const std::string&, c10::IValue&)>& edit) {
  torch::serialize::InputArchive in;
  in.load_from(from);
  torch::serialize::OutputArchive out;
  for (const char* key : {"format", "network", "train", "spec", "state", "params", "target_scaling",
                          "exp_avg", "exp_avg_sq", "digests"}) {
    c10::IValue value;
    if (!in.try_read(key, value)) continue;
    edit(key, value);
    if (value.isNone()) continue;  // dropped
    if (value.isTensor()) {
      out.write(key, value.toTensor());
    } else {
      out.write(key, value);
    }
  }
  out.save_to(to);
}

TEST(CheckpointTest, AnEntryChangedOnDiskIsFoundByItsDigest) {
  const Dataset data = MakeVectorTask(1, 5);
  Trainer trainer(data, NetworkConfig{}, ShortAuthors(5));
  trainer.Train();
  const std::string good = TempPath("digest_good.ckpt");
  trainer.SaveCheckpoint(good);
  EXPECT_FALSE(ReadCheckpointString(good, "digests").empty());
  // One weight a little off (still finite: the NaN check cannot see it), and a configuration
  // that still parses.
  const std::string weight = TempPath("digest_weight.ckpt");
  RewriteCheckpoint(good, weight, [](const std::string& key, c10::IValue& value) {
    if (key == "params") {
      torch::Tensor t = value.toTensor().clone();
      t[0] += 1e-3f;
      value = t;
    }
  });
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(weight); }), HasSubstr("entry 'params' is damaged"));
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(weight, data); }), HasSubstr(weight));
  const std::string moments = TempPath("digest_moments.ckpt");
  RewriteCheckpoint(good, moments, [](const std::string& key, c10::IValue& value) {
    if (key == "exp_avg_sq") value = value.toTensor() + 1;
  });
  // A policy does not use the optimizer's moments, but a checkpoint damaged anywhere is refused.
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(moments); }),
              HasSubstr("entry 'exp_avg_sq' is damaged"));
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(moments, data); }),
              HasSubstr("entry 'exp_avg_sq' is damaged"));
  const std::string config = TempPath("digest_config.ckpt");
  RewriteCheckpoint(good, config, [](const std::string& key, c10::IValue& value) {
    if (key == "train") {
      std::string text = value.toStringRef();
      text.replace(text.find("\"steps\":5"), 9, "\"steps\":6");
      value = c10::IValue(text);
    }
  });
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(config); }), HasSubstr("entry 'train' is damaged"));
  // A checkpoint written before digests existed reads as before.
  const std::string old = TempPath("digest_old.ckpt");
  RewriteCheckpoint(good, old, [](const std::string& key, c10::IValue& value) {
    if (key == "digests") value = c10::IValue();
  });
  EXPECT_TRUE(ReadCheckpointString(old, "digests").empty());
  EXPECT_TRUE(BitwiseEqual(Probe(LoadPolicy(old), data), Probe(trainer.policy(), data)));
  EXPECT_EQ(Trainer::Resume(old, data)->step(), 5);
}

TEST(CheckpointTest, ArchitectureMismatchIsAUserError) {
  const Dataset data = MakeVectorTask(1, 5);
  Trainer trainer(data, NetworkConfig{}, ShortAuthors(5));
  const std::string good = TempPath("arch.ckpt");
  trainer.SaveCheckpoint(good);

  // Rewrite the checkpoint with a configuration that describes other networks.
  torch::serialize::InputArchive in;
  in.load_from(good);
  torch::serialize::OutputArchive out;
  for (const char* key : {"format", "train", "spec", "state"}) {
    c10::IValue value;
    ASSERT_TRUE(in.try_read(key, value));
    out.write(key, value);
  }
  c10::IValue network;
  ASSERT_TRUE(in.try_read("network", network));
  NetworkConfig other = NetworkConfigFromJson(network.toStringRef());
  other.policy_hidden = {16};
  out.write("network", c10::IValue(ToJson(other)));
  for (const char* key : {"params", "target_scaling", "exp_avg", "exp_avg_sq"}) {
    torch::Tensor t;
    in.read(key, t);
    out.write(key, t);
  }
  const std::string bad = TempPath("arch_bad.ckpt");
  out.save_to(bad);
  EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(bad, data); }), HasSubstr("architecture differs"));
  EXPECT_THAT(UserErrorOf([&] { LoadPolicy(bad); }), HasSubstr("architecture differs"));
}

TEST(CheckpointTest, NonFiniteParametersAreRefusedNamingTheTensorAndValue) {
  const Dataset data = MakeVectorTask(1, 5);
  Trainer trainer(data, NetworkConfig{}, ShortAuthors(5));
  const std::string good = TempPath("finite.ckpt");
  trainer.SaveCheckpoint(good);
  for (const char* poisoned : {"params", "target_scaling", "exp_avg_sq"}) {
    for (const float value :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
      torch::serialize::InputArchive in;
      in.load_from(good);
      torch::serialize::OutputArchive out;
      for (const char* key : {"format", "network", "train", "spec", "state"}) {
        c10::IValue v;
        ASSERT_TRUE(in.try_read(key, v));
        out.write(key, v);
      }
      for (const char* key : {"params", "target_scaling", "exp_avg", "exp_avg_sq"}) {
        torch::Tensor t;
        in.read(key, t);
        if (std::string(key) == poisoned) {
          t = t.clone();
          t[1] = value;
        }
        out.write(key, t);
      }
      const std::string bad = TempPath("nonfinite.ckpt");
      out.save_to(bad);
      const std::string expected = std::string("tensor '") + poisoned + "' value 1 of ";
      EXPECT_THAT(UserErrorOf([&] { Trainer::Resume(bad, data); }), HasSubstr(expected));
      if (std::string(poisoned) != "exp_avg_sq") {  // a policy does not read the optimiser
        const std::string message = UserErrorOf([&] { LoadPolicy(bad); });
        EXPECT_THAT(message, HasSubstr(expected));
        EXPECT_THAT(message, HasSubstr(std::isnan(value) ? "is NaN" : "is infinite"));
        EXPECT_THAT(message, HasSubstr(bad));
      }
    }
  }
  EXPECT_NO_THROW(LoadPolicy(good));
}

}  // namespace
}  // namespace recon::learn
