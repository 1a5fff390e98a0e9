// The probe's summary (probe/probe.json): written atomically, read back field for field (a
// read-out that could not be made stays none), and damage named by file and field.

#include "engine/store/probe_summary.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/store/store_test_support.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::ErrorOf;
using ::testing::HasSubstr;
using testing::TempDir;

ProbedObject Moved(double action, double feature, std::optional<double> r2,
                   std::optional<std::string> figure) {
  ProbedObject o;
  o.action_change_per_10cm = action;
  o.feature_change_per_10cm = feature;
  o.readout_r2 = r2;
  o.figure = std::move(figure);
  return o;
}

ProbeSummary TwoMethods() {
  ProbeSummary summary;
  summary.scene_seed = 10380551167851965660ull;
  summary.nx = 10;
  summary.ny = 8;
  summary.bounds = {0.22, 0.82, -0.5, 0.5};
  summary.readout_scenes = 60;
  summary.readout_seed = 6065969806243235080ull;
  summary.seconds = 1.9;
  ProbedMethod recon;
  recon.label = "RECON (Play)";
  recon.model_id = "fnv1a:00c0ffee00c0ffee";
  recon.objects["plate"] = Moved(0.0022, 0.099, 0.997, "probe/recon_plate.png");
  recon.objects["toast"] = Moved(0.0004, 0.005, std::nullopt, std::nullopt);
  ProbedMethod baseline;
  baseline.label = "Baseline";
  baseline.objects["bowl"] = Moved(0.0054, 0.128, -0.06, "probe/baseline_bowl.png");
  // Rolled out whole from each of the grid's 80 places: 1 or 0.
  ProbedObject& rolled = baseline.objects["bowl"];
  for (int cell = 0; cell < 80; ++cell) rolled.outcome.push_back(cell % 2);
  rolled.success_rate = 0.5;
  rolled.home_succeeded = true;
  rolled.outcome_figure = "probe/baseline_bowl_outcome.png";
  summary.methods = {{"recon", recon}, {"baseline", baseline}};
  return summary;
}

TEST(ProbeSummaryTest, IsReadBackFieldForFieldInTheShapeTheCliPrints) {
  const TempDir dir("probe");
  const std::string path = dir.Path("probe.json");
  WriteProbeSummary(path, TwoMethods());
  const json value = json::parse(std::ifstream(path));
  // {"methods": {"<method>": {"<object>": {"action_change_per_10cm": ...}}}}
  EXPECT_DOUBLE_EQ(value["methods"]["recon"]["plate"]["readout_r2"].get<double>(), 0.997);
  EXPECT_TRUE(value["methods"]["recon"]["toast"]["readout_r2"].is_null());
  EXPECT_DOUBLE_EQ(value["methods"]["baseline"]["bowl"]["action_change_per_10cm"].get<double>(),
                   0.0054);
  EXPECT_EQ(value["scene_seed"].get<uint64_t>(), 10380551167851965660ull);
  EXPECT_EQ(ProbeSummaryFromJson(value, path), TwoMethods());
  for (const auto& entry : fs::directory_iterator(dir.Path())) {
    EXPECT_EQ(entry.path().filename(), "probe.json");  // no temporary left
  }
}

TEST(ProbeSummaryTest, KeepsWholeRolloutsAndAReadOutOfRecordedFramesWithNothingMoved) {
  ProbeSummary two = TwoMethods();
  two.methods["baseline"].objects["bowl"].outcome[3] = NAN;  // not rolled out there
  json value = json::parse(ProbeSummaryToJson(two).dump());  // as written to probe.json
  const json& bowl = value["methods"]["baseline"]["bowl"];
  EXPECT_DOUBLE_EQ(bowl["success_rate"].get<double>(), 0.5);
  EXPECT_TRUE(bowl["home_succeeded"].get<bool>());
  EXPECT_TRUE(bowl["outcome"][3].is_null());
  const ProbeSummary back = ProbeSummaryFromJson(value, "probe.json");
  const ProbedObject& rolled = back.methods.at("baseline").objects.at("bowl");
  ASSERT_EQ(rolled.outcome.size(), 80u);
  EXPECT_TRUE(std::isnan(rolled.outcome[3]));
  EXPECT_EQ(rolled.outcome[5], 1.0);
  EXPECT_EQ(rolled.outcome_figure, "probe/baseline_bowl_outcome.png");
  EXPECT_FALSE(back.methods.at("recon").objects.at("plate").success_rate);

  // A real cell's session: read out on recorded frames, nothing moved, no grid.
  ProbeSummary recorded;
  recorded.readout_frames = 412;
  recorded.readout_episodes = 9;
  ProbedObject plate;
  plate.readout_r2 = 0.91;
  recorded.methods["recon"].label = "RECON";
  recorded.methods["recon"].objects["plate"] = plate;
  value = ProbeSummaryToJson(recorded);
  EXPECT_TRUE(value["methods"]["recon"]["plate"]["action_change_per_10cm"].is_null());
  EXPECT_EQ(value["readout"]["recorded_frames"], 412);
  EXPECT_EQ(ProbeSummaryFromJson(value, "probe.json"), recorded);

  value = ProbeSummaryToJson(TwoMethods());
  value["methods"]["baseline"]["bowl"]["outcome"] = {1, 0};
  EXPECT_THAT(ErrorOf([&] { ProbeSummaryFromJson(value, "probe.json"); }), HasSubstr("outcome"));
  value = ProbeSummaryToJson(TwoMethods());
  value["methods"]["baseline"]["bowl"]["outcome_figure"] = "/etc/passwd";
  EXPECT_THAT(ErrorOf([&] { ProbeSummaryFromJson(value, "probe.json"); }),
              HasSubstr("outside the session"));
}

TEST(ProbeSummaryTest, DamageIsNamedByFileAndField) {
  json value = ProbeSummaryToJson(TwoMethods());
  value["methods"]["recon"]["plate"]["action_change_per_10cm"] = "a lot";
  EXPECT_THAT(ErrorOf([&] { ProbeSummaryFromJson(value, "probe.json"); }), HasSubstr("probe.json"));
  EXPECT_THAT(ErrorOf([&] { ProbeSummaryFromJson(value, "probe.json"); }),
              HasSubstr("action_change_per_10cm"));
  value = ProbeSummaryToJson(TwoMethods());
  value["methods"]["recon"]["plate"]["figure"] = "../../etc/passwd";
  EXPECT_THAT(ErrorOf([&] { ProbeSummaryFromJson(value, "probe.json"); }),
              HasSubstr("outside the session"));
  value = ProbeSummaryToJson(TwoMethods());
  value["grid"]["bounds_m"] = {0.1, 0.2};
  EXPECT_THAT(ErrorOf([&] { ProbeSummaryFromJson(value, "probe.json"); }), HasSubstr("bounds_m"));
}

}  // namespace
}  // namespace recon::store
