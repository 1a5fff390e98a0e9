#include "engine/store/rollout_summary.h"

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
using ::testing::Not;
using testing::SmallManifest;
using testing::TempDir;
using testing::WriteText;

// A summary as EvaluateSessionMethod fills one on the tabletop.
RolloutSummary FullSummary() {
  RolloutSummary s;
  s.method = "baseline";
  s.label = "Baseline";
  s.checkpoint = Session::CheckpointRelativePath("baseline");
  s.model_id = "fnv1a:00c0ffee00c0ffee";
  s.metric_name = "distance from the toast to the plate's centre (m, lower is better)";
  s.metric_key = "distance";
  s.higher_is_better = false;
  s.metric_mean = 0.40115;
  s.metric_sem = 0.0015;
  s.has_success = true;
  s.success_rate = 0.5;
  s.success_sem = 0.5;
  s.details = {{"grasped", 0.5}, {"lifted", 0.25}};
  s.tests = 2;
  s.seed = 9778231605760336522u;
  s.seconds = 0.8125;
  s.per_scenario = {{11, 0.4, true, {{"grasped", 1.0}, {"lifted", 0.5}}},
                    {12, 0.4023, false, {{"grasped", 0.0}, {"lifted", 0.0}}}};
  s.replay = Session::RolloutReplayRelativePath("baseline");
  return s;
}

// What EvaluateSessionMethod wrote for FullSummary()'s values before summaries had a type: its
// json built the same way (app/cli/session_training.cc at 02af327).
std::string OldFullSummaryText() {
  json per_scenario = json::array();
  per_scenario.push_back(
      {{"seed", uint64_t{11}},
       {"metric", 0.4},
       {"succeeded", true},
       {"details", std::map<std::string, double>{{"grasped", 1.0}, {"lifted", 0.5}}}});
  per_scenario.push_back(
      {{"seed", uint64_t{12}},
       {"metric", 0.4023},
       {"succeeded", false},
       {"details", std::map<std::string, double>{{"grasped", 0.0}, {"lifted", 0.0}}}});
  json record = {
      {"method", "baseline"},
      {"label", "Baseline"},
      {"checkpoint", fs::path("checkpoints") / "baseline.ckpt"},
      {"model_id", "fnv1a:00c0ffee00c0ffee"},
      {"metric_name", "distance from the toast to the plate's centre (m, lower is better)"},
      {"metric_key", "distance"},
      {"higher_is_better", false},
      {"metric_mean", 0.40115},
      {"metric_sem", 0.0015},
      {"has_success", true},
      {"success_rate", 0.5},
      {"success_sem", 0.5},
      {"details", std::map<std::string, double>{{"grasped", 0.5}, {"lifted", 0.25}}},
      {"tests", 2},
      {"seed", uint64_t{9778231605760336522u}},
      {"seconds", 0.8125},
      {"per_scenario", per_scenario}};
  record["replay"] = (fs::path("rollouts") / "baseline.replay.h5").string();
  return record.dump(1) + "\n";
}

TEST(RolloutSummaryTest, ASummaryReadsBackAsItWasWritten) {
  TempDir dir("rollouts-roundtrip");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  EXPECT_FALSE(ReadRolloutSummary(session, "baseline").has_value());
  fs::create_directories(fs::path(session.RolloutSummaryPath("baseline")).parent_path());
  const RolloutSummary written = FullSummary();
  WriteRolloutSummary(session.RolloutSummaryPath("baseline"), written);
  const std::optional<RolloutSummary> read = ReadRolloutSummary(session, "baseline");
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(*read, written);

  // No replay, no model id (null in the file), and a mean of nothing (NaN, written as null).
  RolloutSummary recon = FullSummary();
  recon.method = "recon";
  recon.replay.reset();
  recon.model_id.reset();
  recon.metric_sem = std::nan("");
  WriteRolloutSummary(session.RolloutSummaryPath("recon"), recon);
  EXPECT_THAT(Bytes(session.RolloutSummaryPath("recon")), HasSubstr("\"model_id\": null"));
  EXPECT_THAT(Bytes(session.RolloutSummaryPath("recon")), Not(HasSubstr("\"replay\"")));
  const std::map<std::string, RolloutSummary> all = ReadRolloutSummaries(session);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all.at("baseline"), written);
  const RolloutSummary& back = all.at("recon");
  EXPECT_FALSE(back.replay.has_value());
  EXPECT_FALSE(back.model_id.has_value());
  EXPECT_TRUE(std::isnan(back.metric_sem));
  EXPECT_EQ(back.per_scenario, recon.per_scenario);
}

TEST(RolloutSummaryTest, TheFileIsByteForByteWhatTheUntypedSummaryWas) {
  TempDir dir("rollouts-bytes");
  const std::string path = dir.Path("baseline.json");
  WriteRolloutSummary(path, FullSummary());
  EXPECT_EQ(Bytes(path), OldFullSummaryText());
  const RolloutSummary read = RolloutSummaryFromJson(json::parse(Bytes(path)), path, "baseline");
  WriteRolloutSummary(path, read);
  EXPECT_EQ(Bytes(path), OldFullSummaryText());
}

TEST(RolloutSummaryTest, KeysASummaryFromBeforeLacksReadAsTheirDefaults) {
  TempDir dir("rollouts-old");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  // From before model ids and replays, and with its label, name and details gone.
  WriteText(session.RolloutSummaryPath("recon"), R"({
 "checkpoint": "checkpoints/recon.ckpt", "metric_mean": 6.22, "tests": 2, "seed": 5,
 "per_scenario": [{"seed": 1, "metric": 6.0, "succeeded": false}]
})");
  const std::optional<RolloutSummary> s = ReadRolloutSummary(session, "recon");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->method, "recon");
  EXPECT_EQ(s->label, "recon");
  EXPECT_EQ(s->metric_name, "metric");  // as the report and `session info` showed it
  EXPECT_EQ(s->metric_mean, 6.22);
  EXPECT_EQ(s->metric_sem, 0.0);
  EXPECT_FALSE(s->has_success);
  EXPECT_FALSE(s->higher_is_better);
  EXPECT_EQ(s->tests, 2);
  EXPECT_FALSE(s->model_id.has_value());
  EXPECT_FALSE(s->replay.has_value());
  EXPECT_TRUE(s->details.empty());
  ASSERT_EQ(s->per_scenario.size(), 1u);
  EXPECT_EQ(s->per_scenario[0].seed, 1u);
  EXPECT_TRUE(s->per_scenario[0].details.empty());
}

TEST(RolloutSummaryTest, AMalformedSummaryIsRefusedNamingTheFileAndTheField) {
  TempDir dir("rollouts-bad");
  const Session session = Session::Create(dir.Path("s"), SmallManifest());
  const std::string path = session.RolloutSummaryPath("baseline");
  const auto error_for = [&](const std::string& text) {
    WriteText(path, text);
    return ErrorOf([&] { ReadRolloutSummary(session, "baseline"); });
  };
  EXPECT_EQ(error_for(R"({"tests": 2.5})"), path + ": field 'tests' must be an integer");
  EXPECT_EQ(error_for(R"({"has_success": "yes"})"),
            path + ": field 'has_success' must be true or false");
  EXPECT_EQ(error_for(R"({"details": {"grasped": "often"}})"),
            path + ": field 'details.grasped' must be a number");
  EXPECT_EQ(error_for(R"({"per_scenario": {}})"), path + ": field 'per_scenario' must be a list");
  EXPECT_EQ(error_for(R"({"per_scenario": [{"seed": -1}]})"),
            path + ": field 'per_scenario[0].seed' must be a non-negative integer");
  EXPECT_EQ(error_for(R"({"per_scenario": [{}, 3]})"),
            path + ": field 'per_scenario[1]' must be an object");
  EXPECT_EQ(error_for(R"({"replay": false})"), path + ": field 'replay' must be a string");
  EXPECT_THAT(error_for("not json"), HasSubstr(path + ": not valid JSON"));
}

}  // namespace
}  // namespace recon::store
