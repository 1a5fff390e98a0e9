#include "engine/experiments/experiment.h"
#include "engine/experiments/evaluation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/experiments/summary.h"

namespace recon::experiments {
namespace {

namespace fs = std::filesystem;

ExperimentConfig ShortConfig() {
  ExperimentConfig config;
  config.world = "dynamic2d";
  config.conditions = ParseConditions("dynamic2d", {"baseline", "exact"}, {});
  config.demos = {3};
  config.runs = 2;
  config.tests = 8;
  config.seed = 11;
  config.jobs = 2;
  config.train.steps = 40;
  config.baseline_steps = 30;
  return config;
}

TEST(ExperimentTest, SeedsArePairedAndPrefixed) {
  // Run r's first demos are the same whatever the demo count, and differ between runs.
  EXPECT_EQ(DemoScenarioSeed(1, 0, 2), DemoScenarioSeed(1, 0, 2));
  EXPECT_NE(DemoScenarioSeed(1, 0, 2), DemoScenarioSeed(1, 1, 2));
  EXPECT_NE(TestScenarioSeed(1, 0), DemoScenarioSeed(1, 0, 0));
  EXPECT_NE(TrainSeed(1, 0), TrainSeed(1, 1));
  EXPECT_NE(TestScenarioSeed(1, 3), TestScenarioSeed(2, 3));
}

TEST(ExperimentTest, ShortRunProducesATableAndIsReproducible) {
  const ExperimentConfig config = ShortConfig();
  int observed = 0;
  const ExperimentResult a = RunExperiment(config, [&](const RunResult&) { ++observed; });
  EXPECT_EQ(observed, 4);
  ASSERT_EQ(a.runs.size(), 4u);
  EXPECT_EQ(a.runs[0].condition, "baseline");
  EXPECT_EQ(a.runs[0].run, 0);
  EXPECT_EQ(a.runs[1].run, 1);
  EXPECT_EQ(a.runs[2].condition, "exact");
  EXPECT_EQ(a.runs[0].train_steps, 30);
  EXPECT_EQ(a.runs[2].train_steps, 40);
  for (const RunResult& r : a.runs) {
    EXPECT_TRUE(std::isfinite(r.metric)) << r.condition;
    EXPECT_GT(r.metric, 0.0);
    EXPECT_LT(r.metric, 40.0);
  }
  EXPECT_NEAR(a.expert_metric, 17.785, 1e-3);
  EXPECT_TRUE(a.higher_is_better);

  // Same seed, different thread count and order: identical numbers.
  ExperimentConfig serial = config;
  serial.jobs = 1;
  const ExperimentResult b = RunExperiment(serial);
  ASSERT_EQ(b.runs.size(), a.runs.size());
  for (size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_EQ(a.runs[i].metric, b.runs[i].metric) << i;
    EXPECT_EQ(a.runs[i].train_seed, b.runs[i].train_seed);
  }
  // Paired design: both conditions of a run saw the same training seed.
  EXPECT_EQ(a.runs[0].train_seed, a.runs[2].train_seed);
}

TEST(ExperimentTest, ADetailIsAveragedOverTheScenariosThatReportIt) {
  std::vector<ScenarioOutcome> outcomes(3);
  outcomes[0].details = {{"grasped", 1.0}, {"feature_gate_after_grasp", 0.8}};
  outcomes[1].details = {{"grasped", 0.0}};
  outcomes[2].details = {{"grasped", 1.0}, {"feature_gate_after_grasp", 0.6}};
  const std::map<std::string, double> mean = MeanDetails(outcomes);
  EXPECT_NEAR(mean.at("grasped"), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(mean.at("feature_gate_after_grasp"), 0.7, 1e-12);  // not (0.8 + 0.6) / 3
}

TEST(ExperimentTest, OutputsAreWrittenAndSummaryHasTheDocumentedShape) {
  const ExperimentConfig config = ShortConfig();
  const ExperimentResult result = RunExperiment(config);
  const fs::path dir = fs::path(testing::TempDir()) / "experiment_outputs";
  fs::remove_all(dir);
  const auto written = WriteExperimentOutputs(config, result, dir.string());
  for (const char* name :
       {"dynamic2d.png", "dynamic2d.svg", "losses.png", "results.csv", "summary.json"}) {
    EXPECT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_GT(fs::file_size(dir / name), 100u) << name;
  }
  std::ifstream in(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  ASSERT_TRUE(summary["conditions"].contains("exact"));
  const auto& exact = summary["conditions"]["exact"];
  EXPECT_EQ(exact["n"], 2);
  EXPECT_EQ(exact["train_steps"], 40);
  EXPECT_EQ(summary["conditions"]["baseline"]["train_steps"], 30);
  const double mean = (result.runs[2].metric + result.runs[3].metric) / 2.0;
  EXPECT_NEAR(exact["mean"].get<double>(), mean, 1e-9);
  EXPECT_GT(exact["sem"].get<double>(), 0.0);
  EXPECT_TRUE(summary["wall_seconds"].is_number());
  EXPECT_EQ(summary["seeds"]["seed"], 11);

  std::ifstream csv(dir / "results.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 5);  // header + 2 conditions x 2 runs
}

TEST(ExperimentTest, DemoSweepWritesTheDataEfficiencyCurve) {
  ExperimentConfig config = ShortConfig();
  config.conditions = ParseConditions("static2d", {"baseline", "recon-p-play"}, {});
  config.world = "static2d";
  config.demos = {2, 4};
  config.runs = 1;
  const ExperimentResult result = RunExperiment(config);
  EXPECT_EQ(result.runs.size(), 4u);
  EXPECT_FALSE(result.higher_is_better);
  const fs::path dir = fs::path(testing::TempDir()) / "experiment_sweep";
  fs::remove_all(dir);
  WriteExperimentOutputs(config, result, dir.string());
  EXPECT_TRUE(fs::exists(dir / "data_efficiency.png"));
  std::ifstream in(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_TRUE(summary["by_demos"].contains("2"));
  EXPECT_TRUE(summary["by_demos"].contains("4"));
}

TEST(ExperimentTest, BadConfigurationIsAUserError) {
  ExperimentConfig config = ShortConfig();
  config.demos = {0};
  EXPECT_THROW(RunExperiment(config), UserError);
  config = ShortConfig();
  config.network.feature_dim = 2;  // Exact has d = 2: k must exceed it
  EXPECT_THROW(RunExperiment(config), UserError);
}

}  // namespace
}  // namespace recon::experiments
