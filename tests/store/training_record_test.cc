#include "engine/store/training_record.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/store/store_test_support.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::Bytes;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::SmallManifest;
using testing::TempDir;
using testing::WriteText;

// A record as TrainSessionMethod fills one: the losses are floats widened to double.
TrainingRecord FullRecord() {
  TrainingRecord r;
  r.method = "recon";
  r.label = "RECON (Play)";
  r.checkpoint = Session::CheckpointRelativePath("recon");
  r.model_id = "fnv1a:00c0ffee00c0ffee";
  r.trained_on = TrainedOn{{"demo_0", "demo_2", "play_0"}, false, true};
  r.steps = 15000;
  r.attempts = 2;
  r.seconds = 812.375;
  r.seed = 14646652180046636950u;
  r.loss = "nll";
  r.batch = 20;
  r.learning_rate = 1e-3;
  r.feature_dim = 6;
  r.play_consistency = 1.0;
  r.nll_min_std = 0.05;
  r.action_min_std = {0, 0, 0.1};
  r.train_demos = 3;
  r.train_samples = 435;
  r.play_samples = 1;
  r.valid_demos = 1;
  r.final_losses = {0.1f, 2.7f, 1.3f, 0.01f, -4.2f};
  r.train_action_mse = 0.012345678901234;
  r.valid_action_mse = 0.0456;
  r.history.Append(37, {2.5598275661468506, 0.5, 0.25, 0.125, 3.0});
  r.history.Append(112, {1.75, 0.375, 0.1875, 0.0625, -1.5});
  return r;
}

// What TrainSessionMethod wrote for FullRecord()'s values before records had a type: its json
// built the same way (app/cli/session_training.cc at 02af327), so a file written now is the
// file written then.
std::string OldFullRecordText() {
  json history = {{"step", json::array()},
                  {"action_loss", json::array()},
                  {"beacon_loss", json::array()},
                  {"play_loss", json::array()},
                  {"consistency_loss", json::array()},
                  {"total_loss", json::array()}};
  for (const auto& [step, a, b, p, c, t] :
       {std::tuple{37, 2.5598275661468506, 0.5, 0.25, 0.125, 3.0},
        std::tuple{112, 1.75, 0.375, 0.1875, 0.0625, -1.5}}) {
    history["step"].push_back(step);
    history["action_loss"].push_back(a);
    history["beacon_loss"].push_back(b);
    history["play_loss"].push_back(p);
    history["total_loss"].push_back(t);
    history["consistency_loss"].push_back(c);
  }
  const std::vector<std::string> trained_on = {"demo_0", "demo_2", "play_0"};
  const json record = {
      {"method", "recon"},
      {"label", "RECON (Play)"},
      {"checkpoint", fs::path("checkpoints") / "recon.ckpt"},
      {"steps", 15000},
      {"attempts", 2},
      {"seconds", 812.375},
      {"seed", uint64_t{14646652180046636950u}},
      {"loss", "nll"},
      {"batch", 20},
      {"learning_rate", 1e-3},
      {"feature_dim", 6},
      {"play_consistency", 1.0},
      {"nll_min_std", 0.05},
      {"action_min_std", std::vector<double>{0, 0, 0.1}},
      {"train_demos", size_t{3}},
      {"train_samples", int64_t{435}},
      {"play_samples", size_t{1}},
      {"valid_demos", size_t{1}},
      {"trained_on", {{"episodes", trained_on}, {"include_bad", false}, {"use_play", true}}},
      {"model_id", "fnv1a:00c0ffee00c0ffee"},
      {"final",
       {{"action_loss", 0.1f},
        {"beacon_loss", 2.7f},
        {"play_loss", 1.3f},
        {"consistency_loss", 0.01f},
        {"total_loss", -4.2f}}},
      {"train_action_mse", 0.012345678901234},
      {"valid_action_mse", json(0.0456)},
      {"history", history}};
  return record.dump(1) + "\n";
}

TEST(TrainingRecordTest, ARecordReadsBackAsItWasWritten) {
  TempDir dir("training-roundtrip");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  EXPECT_FALSE(ReadTrainingRecord(session, "recon").has_value());
  fs::create_directories(fs::path(session.TrainingRecordPath("recon")).parent_path());
  const TrainingRecord written = FullRecord();
  WriteTrainingRecord(session.TrainingRecordPath("recon"), written);
  const std::optional<TrainingRecord> read = ReadTrainingRecord(session, "recon");
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(*read, written);

  // Without validation demonstrations, and with a loss that diverged (written as null).
  TrainingRecord baseline = FullRecord();
  baseline.method = "baseline";
  baseline.label = "Baseline";
  baseline.valid_action_mse.reset();
  baseline.history.total_loss[1] = std::nan("");
  WriteTrainingRecord(session.TrainingRecordPath("baseline"), baseline);
  const std::map<std::string, TrainingRecord> all = ReadTrainingRecords(session);
  ASSERT_EQ(all.size(), 2u);
  const TrainingRecord& back = all.at("baseline");
  EXPECT_FALSE(back.valid_action_mse.has_value());
  EXPECT_TRUE(std::isnan(back.history.total_loss[1]));
  EXPECT_EQ(back.history.total_loss[0], 3.0);
  EXPECT_EQ(all.at("recon"), written);

  // The chunk length a model was trained with, where known, is kept.
  TrainingRecord chunked = FullRecord();
  chunked.action_chunk = 20;
  WriteTrainingRecord(session.TrainingRecordPath("recon"), chunked);
  EXPECT_EQ(ReadTrainingRecord(session, "recon")->action_chunk, 20);
}

TEST(TrainingRecordTest, TheFileIsByteForByteWhatTheUntypedRecordWas) {
  TempDir dir("training-bytes");
  const std::string path = dir.Path("recon.json");
  WriteTrainingRecord(path, FullRecord());
  EXPECT_EQ(Bytes(path), OldFullRecordText());
  // Read and written again, a file stays as it was.
  const TrainingRecord read =
      TrainingRecordFromJson(json::parse(Bytes(path)), path, "ignored: the record says");
  EXPECT_EQ(read.method, "recon");
  WriteTrainingRecord(path, read);
  EXPECT_EQ(Bytes(path), OldFullRecordText());
}

TEST(TrainingRecordTest, KeysARecordFromBeforeLacksReadAsTheirDefaults) {
  TempDir dir("training-old");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  // A record of the first format (no ids, no episodes, no play consistency), and its label gone.
  WriteText(session.TrainingRecordPath("baseline"), R"({
 "checkpoint": "checkpoints/baseline.ckpt",
 "final": {"action_loss": 2.5, "beacon_loss": 0.0, "play_loss": 0.0, "total_loss": 2.5},
 "history": {"action_loss": [3.0, 2.5], "beacon_loss": [0.0, 0.0], "play_loss": [0.0, 0.0],
             "step": [1, 2], "total_loss": [3.0, 2.5]},
 "steps": 30, "seed": 7, "train_action_mse": 0.06, "valid_action_mse": null
})");
  const std::optional<TrainingRecord> r = ReadTrainingRecord(session, "baseline");
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->method, "baseline");  // the file's name
  EXPECT_EQ(r->label, "baseline");   // the method, as the report showed it
  EXPECT_EQ(r->steps, 30);
  EXPECT_EQ(r->seed, 7u);
  EXPECT_FALSE(r->model_id.has_value());
  EXPECT_FALSE(r->trained_on.has_value());
  EXPECT_EQ(r->play_consistency, 0.0);
  EXPECT_TRUE(r->action_min_std.empty());
  EXPECT_EQ(r->final_losses.total_loss, 2.5);
  EXPECT_EQ(r->final_losses.consistency_loss, 0.0);
  EXPECT_EQ(r->history.step, (std::vector<int64_t>{1, 2}));
  EXPECT_TRUE(r->history.consistency_loss.empty());
  EXPECT_FALSE(r->valid_action_mse.has_value());
  EXPECT_EQ(r->seconds, 0.0);
  EXPECT_EQ(r->train_demos, 0);

  WriteText(session.TrainingRecordPath("recon"), "{}");
  const std::optional<TrainingRecord> empty = ReadTrainingRecord(session, "recon");
  ASSERT_TRUE(empty.has_value());
  EXPECT_EQ(empty->label, "recon");
  EXPECT_TRUE(std::isnan(empty->train_action_mse));
  EXPECT_TRUE(empty->history.step.empty());
}

TEST(TrainingRecordTest, AMalformedRecordIsRefusedNamingTheFileAndTheField) {
  TempDir dir("training-bad");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  const std::string path = session.TrainingRecordPath("recon");
  const auto error_for = [&](const std::string& text) {
    WriteText(path, text);
    return ErrorOf([&] { ReadTrainingRecord(session, "recon"); });
  };
  EXPECT_EQ(error_for(R"({"steps": "many"})"), path + ": field 'steps' must be an integer");
  EXPECT_EQ(error_for(R"({"seed": -3})"), path + ": field 'seed' must be a non-negative integer");
  EXPECT_EQ(error_for(R"({"history": {"action_loss": [1.0, "x"]}})"),
            path + ": field 'history.action_loss[1]' must be a number");
  EXPECT_EQ(error_for(R"({"history": {"step": [1.5]}})"),
            path + ": field 'history.step[0]' must be an integer");
  EXPECT_EQ(error_for(R"({"trained_on": {"episodes": [3]}})"),
            path + ": field 'trained_on.episodes[0]' must be a string");
  EXPECT_EQ(error_for(R"({"final": [1, 2]})"), path + ": field 'final' must be an object");
  EXPECT_EQ(error_for(R"({"model_id": 12})"), path + ": field 'model_id' must be a string");
  EXPECT_EQ(error_for(R"({"valid_action_mse": "low"})"),
            path + ": field 'valid_action_mse' must be a number");
  EXPECT_EQ(error_for("[1, 2]"), path + ": field '(top level)' must be an object");
  EXPECT_THAT(error_for(R"({"steps": )"), HasSubstr(path + ": not valid JSON"));
  // Listing them all refuses the same way.
  EXPECT_THAT(ErrorOf([&] { ReadTrainingRecords(session); }), HasSubstr(path));
}

TEST(TrainingRecordTest, TheSessionNamesEveryResultFileOfAMethod) {
  TempDir dir("result-paths");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  const fs::path s = dir.Path("s");
  EXPECT_EQ(session.CheckpointPath("recon"), (s / "checkpoints" / "recon.ckpt").string());
  EXPECT_EQ(session.TrainingRecordPath("recon"), (s / "training" / "recon.json").string());
  EXPECT_EQ(session.RolloutSummaryPath("baseline"), (s / "rollouts" / "baseline.json").string());
  EXPECT_EQ(session.RolloutReplayPath("baseline"),
            (s / "rollouts" / "baseline.replay.h5").string());
  // Records name them relative to the session, as they always have.
  EXPECT_EQ(Session::CheckpointRelativePath("baseline"), "checkpoints/baseline.ckpt");
  EXPECT_EQ(Session::RolloutReplayRelativePath("recon"), "rollouts/recon.replay.h5");
}

}  // namespace
}  // namespace recon::store
