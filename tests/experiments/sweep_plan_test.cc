// An experiment as a plan of independent units: the units are the runs RunExperiment makes,
// each unit run alone gives the same result bytes as the whole experiment's, whatever the order;
// the plan and unit files read back field for field, and a plan edited by hand, a truncated unit
// or a unit of another index is refused by name.

#include "engine/experiments/sweep_plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "engine/experiments/summary.h"

namespace recon::experiments {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

ExperimentConfig TwoByTwo() {
  ExperimentConfig config;
  config.world = "dynamic2d";
  config.conditions = ParseConditions("dynamic2d", {"baseline", "exact"}, {});
  config.demos = {3, 5};
  config.runs = 2;
  config.tests = 6;
  config.seed = 11;
  config.jobs = 2;
  config.train.steps = 40;
  config.baseline_steps = 30;
  return config;
}

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("sweep_plan_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SweepPlanTest, UnitsRunAloneInAnyOrderGiveTheExperimentsRunsByteForByte) {
  const ExperimentConfig config = TwoByTwo();
  const std::vector<ExperimentUnit> units = PlanUnits(config);
  ASSERT_EQ(units.size(), 8u);  // 2 runs x 2 demo counts x 2 conditions, run-major
  EXPECT_EQ(units[0].run, 0);
  EXPECT_EQ(units[3].demos, 5);
  EXPECT_EQ(units[4].run, 1);
  for (size_t i = 0; i < units.size(); ++i) EXPECT_EQ(units[i].index, static_cast<int>(i));

  const ExperimentResult whole = RunExperiment(config);
  std::vector<UnitResult> alone;
  for (auto it = units.rbegin(); it != units.rend(); ++it) alone.push_back(RunUnit(config, *it));
  const ExperimentResult assembled = AssembleExperiment(config, DescribeExperiment(config), alone);
  ASSERT_EQ(assembled.runs.size(), whole.runs.size());
  for (size_t i = 0; i < whole.runs.size(); ++i) {
    UnitResult a{units[0], assembled.runs[i], std::nullopt},
        b{units[0], whole.runs[i], std::nullopt};
    EXPECT_EQ(UnitResultText(a), UnitResultText(b)) << "run " << i;
  }
  ASSERT_EQ(assembled.loss_curves.size(), whole.loss_curves.size());
  for (size_t i = 0; i < whole.loss_curves.size(); ++i) {
    EXPECT_EQ(assembled.loss_curves[i].action_loss, whole.loss_curves[i].action_loss);
  }
  EXPECT_EQ(assembled.expert_metric, whole.expert_metric);

  // Part of the units: the table has what is done, in order.
  const ExperimentResult part =
      AssembleExperiment(config, DescribeExperiment(config), {alone[0], alone[7]});
  ASSERT_EQ(part.runs.size(), 2u);
  EXPECT_EQ(part.runs[0].run, 0);  // unit 0 (3 demos, baseline, run 0) comes first
  EXPECT_EQ(part.runs[1].run, 1);
}

TEST(SweepPlanTest, ThePlanAndItsUnitsReadBackAndDamageIsRefusedByName) {
  const ExperimentConfig config = TwoByTwo();
  const fs::path dir = Scratch("files");
  const SweepPlan plan = MakeSweepPlan(config, {"dynamic2d", "--runs", "2"}, "recon test");
  WriteSweepPlan(dir.string(), plan);
  const SweepPlan back = ReadSweepPlan(dir.string());
  EXPECT_EQ(back.arguments, plan.arguments);
  EXPECT_EQ(back.units.size(), 8u);
  EXPECT_EQ(back.train_seeds, plan.train_seeds);
  EXPECT_EQ(back.described.expert_metric, plan.described.expert_metric);  // exact, not near

  const UnitResult result = RunUnit(config, plan.units[2]);
  WriteUnitResult(dir.string(), plan, result, 1.5, "node7");
  const std::optional<UnitResult> read = ReadUnitResult(dir.string(), 2);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(UnitResultText(*read), UnitResultText(result));
  EXPECT_EQ(read->run.train_seconds, 1.5);
  EXPECT_EQ(ReadText(UnitPath(dir.string(), 2)), UnitResultText(result));
  EXPECT_FALSE(ReadUnitResult(dir.string(), 3).has_value());  // not done

  // Damage: a truncated unit, a unit filed under another index, an edited or missing plan.
  const std::string text = UnitResultText(result);
  std::ofstream(UnitPath(dir.string(), 2)) << text.substr(0, text.size() / 2);
  EXPECT_THROW(ReadUnitResult(dir.string(), 2), UserError);
  std::ofstream(UnitPath(dir.string(), 5)) << text;
  try {
    ReadUnitResult(dir.string(), 5);
    ADD_FAILURE() << "a unit of another index was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("holds unit 2, not 5"));
  }
  std::string edited = ReadText(PlanPath(dir.string()));
  edited.replace(edited.find("\"2\""), 3, "\"3\"");
  std::ofstream(PlanPath(dir.string())) << edited;
  try {
    ReadSweepPlan(dir.string());
    ADD_FAILURE() << "an edited plan was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("changed since it was written"));
  }
  fs::remove(PlanPath(dir.string()));
  EXPECT_THROW(ReadSweepPlan(dir.string()), UserError);
  fs::remove_all(dir);
}

// A unit's result is filed only into the plan it ran from: a plan replaced while the unit ran
// (a plan nothing had run from is replaced without --force) or removed gets nothing.
TEST(SweepPlanTest, AUnitOfAReplacedPlanIsNotFiledIntoTheNewOne) {
  const ExperimentConfig config = TwoByTwo();
  const fs::path dir = Scratch("replaced");
  const SweepPlan first = MakeSweepPlan(config, {"dynamic2d", "--runs", "2"}, "recon test");
  WriteSweepPlan(dir.string(), first);
  const UnitResult result = RunUnit(config, first.units[1]);
  // Meanwhile another sweep's plan takes the folder.
  const SweepPlan second =
      MakeSweepPlan(config, {"dynamic2d", "--runs", "2", "--seed", "9"}, "recon test");
  WriteSweepPlan(dir.string(), second);
  try {
    WriteUnitResult(dir.string(), first, result, 1.0, "node1");
    ADD_FAILURE() << "a unit of the replaced plan was filed into the new one";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("replaced by the plan of another sweep while unit 1 ran"));
    EXPECT_THAT(e.what(), HasSubstr("was not written"));
  }
  EXPECT_FALSE(fs::exists(UnitPath(dir.string(), 1)));
  EXPECT_FALSE(ReadUnitResult(dir.string(), 1).has_value());
  // Removed altogether: the same.
  fs::remove(PlanPath(dir.string()));
  EXPECT_THROW(WriteUnitResult(dir.string(), first, result, 1.0, "node1"), UserError);
  EXPECT_FALSE(fs::exists(UnitPath(dir.string(), 1)));
  // Into its own plan it is filed.
  WriteSweepPlan(dir.string(), first);
  WriteUnitResult(dir.string(), first, result, 1.0, "node1");
  EXPECT_TRUE(ReadUnitResult(dir.string(), 1).has_value());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon::experiments
