// The simulated cell's commands, run through the real `recon` binary.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/app/run_recon.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using recon::testing::CommandResult;
using recon::testing::RunRecon;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("cell_cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

nlohmann::json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(CellCliTest, RenderWritesTheTabletopCameraImage) {
  const fs::path out = FreshDir("render") / "tabletop.png";
  const CommandResult r =
      RunRecon("render --scene tabletop --seed 3 --width 320 --height 240 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream png(out, std::ios::binary);
  std::array<unsigned char, 24> header{};
  png.read(reinterpret_cast<char*>(header.data()), header.size());
  EXPECT_EQ(header[1], 'P');
  EXPECT_EQ(header[2], 'N');
  EXPECT_EQ(header[3], 'G');
  // IHDR width and height, big-endian.
  EXPECT_EQ((header[18] << 8) | header[19], 320);
  EXPECT_EQ((header[22] << 8) | header[23], 240);
}

TEST(CellCliTest, RenderOfAMissingOrBrokenSceneIsAClearError) {
  const fs::path dir = FreshDir("render_bad");
  CommandResult r = RunRecon("render --scene kitchen --out " + (dir / "x.png").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("unknown scene 'kitchen'"));
  EXPECT_THAT(r.output, HasSubstr("tabletop"));

  r = RunRecon("render --scene " + (dir / "missing.xml").string() + " --out " +
               (dir / "x.png").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("does not exist"));

  const fs::path broken = dir / "broken.xml";
  std::ofstream(broken) << "<mujoco><worldbody><geom type=\"box\" size=\"1\"></worldbody>";
  r = RunRecon("render --scene " + broken.string() + " --out " + (dir / "x.png").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(broken.string()));
  EXPECT_THAT(r.output, HasSubstr("invalid"));
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(CellCliTest, CalibrateSimPrintsTheFitAndSavesIt) {
  const fs::path out = FreshDir("calibrate") / "calibration.json";
  const CommandResult r = RunRecon("calibrate --sim --points 8 --seed 4 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::ContainsRegex("RMSE [0-9]+\\.[0-9]+ m"));
  EXPECT_THAT(r.output, HasSubstr("PASS"));
  EXPECT_THAT(r.output, HasSubstr("hidden UWB frame recovered"));
  const nlohmann::json saved = ReadJson(out);
  EXPECT_TRUE(saved.contains("version"));
}

TEST(CellCliTest, CalibrateWithoutSimOrWithTooFewPointsIsRefused) {
  CommandResult r = RunRecon("calibrate --points 8");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--sim"));
  r = RunRecon("calibrate --sim --points 2");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = RunRecon("calibrate --sim --dim 4d");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--dim"));
}

TEST(CellCliTest, BinTransferExperimentScoresActionError) {
  const fs::path out = FreshDir("bintransfer");
  const CommandResult r = RunRecon(
      "experiment bintransfer --runs 1 --tests 3 --demos 2 --steps 40 --baseline-steps 30 "
      "--conditions baseline,recon-p-play --out " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["metric"]["key"], "action_mse");
  const auto& baseline = summary["conditions"]["baseline"];
  EXPECT_GT(baseline["action_mse"].get<double>(), 0.0);
  EXPECT_EQ(baseline["n"], 1);
  EXPECT_TRUE(summary["conditions"].contains("recon-p-play"));
  EXPECT_FALSE(baseline.contains("success_rate")) << "the expert drives: no policy success";
  EXPECT_TRUE(summary.contains("teaching_time"));
  EXPECT_TRUE(fs::exists(out / "bintransfer.png"));
}

TEST(CellCliTest, TabletopExperimentReportsSuccessDistanceAndTeachingTime) {
  const fs::path out = FreshDir("tabletop");
  const CommandResult r = RunRecon(
      "experiment tabletop --runs 1 --tests 2 --demos 2,4 --steps 20 --baseline-steps 20 "
      "--image-size 32 --seed 3 --out " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("success"));
  const nlohmann::json summary = ReadJson(out / "summary.json");
  for (const char* demos : {"2", "4"}) {
    for (const char* condition : {"baseline", "recon-play"}) {
      const auto& block = summary["by_demos"][demos]["conditions"][condition];
      ASSERT_TRUE(block.is_object()) << demos << " " << condition;
      for (const char* key : {"success_rate", "distance", "sem", "n"}) {
        EXPECT_TRUE(block.contains(key)) << key;
      }
      for (const char* key :
           {"grip_nearer_bowl", "grasped", "closest_approach_m", "closes_on_nothing"}) {
        EXPECT_TRUE(block["details"].contains(key)) << key << ": " << block.dump();
      }
      EXPECT_GE(block["success_rate"].get<double>(), 0.0);
      EXPECT_LE(block["success_rate"].get<double>(), 1.0);
    }
  }
  // The protocol and the recipe's levers are in the summary, so a run can be repeated.
  EXPECT_EQ(summary["protocol"]["layout"], "paper");
  EXPECT_DOUBLE_EQ(summary["protocol"]["demo_noise"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(summary["train"]["nll_min_std"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(summary["protocol"]["beacon_noise"]["recon-play"].get<double>(), 0.07);
  EXPECT_EQ(summary["network"]["action_chunk"], 10);
  EXPECT_EQ(summary["train"]["random_shift_px"], 4);
  EXPECT_DOUBLE_EQ(summary["train"]["feature_noise"].get<double>(), 0.0);
  EXPECT_EQ(summary["train"]["random_erase_px"], 0);
  // Where it was measured: the same seeds train other models on another CPU or kernel table.
  const std::string kernels = summary["machine"]["kernels"].get<std::string>();
  EXPECT_TRUE(kernels == "generic" || kernels == "avx2" || kernels == "avx512") << kernels;
  EXPECT_THAT(r.output, HasSubstr("kernels " + kernels + " on "));
  EXPECT_FALSE(summary["machine"]["cpu"].get<std::string>().empty());
  const auto& time = summary["teaching_time"];
  // The scripted teacher takes about 13.5 s (the paper's people took 16.6 s).
  const double per_demo = time["seconds_per_demonstration"].get<double>();
  EXPECT_GT(per_demo, 10.0);
  EXPECT_LT(per_demo, 20.0);
  const auto& two = time["by_demos"]["2"];
  // RECON (Play) costs the demonstrations plus two beacon placements plus the play data.
  EXPECT_NEAR(two["baseline"]["total_s"].get<double>(), 2 * per_demo, 1e-9);
  EXPECT_NEAR(two["recon-play"]["total_s"].get<double>(), 2 * per_demo + 4.6 + 2.0, 1e-9);
  EXPECT_TRUE(fs::exists(out / "success.png"));
  EXPECT_TRUE(fs::exists(out / "data_efficiency.png"));
  // Each run's outcome details are columns of results.csv, one value per run.
  std::ifstream csv(out / "results.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_THAT(header, HasSubstr(",success_rate,"));
  EXPECT_THAT(header, HasSubstr(",grasped"));
  EXPECT_THAT(header, HasSubstr(",grip_nearer_bowl"));
  ASSERT_TRUE(std::getline(csv, row));
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(header.begin(), header.end(), ','))
      << header << "\n"
      << row;
}

// The protocol's options: each bad value names its option, exits 2 and writes nothing.
TEST(CellCliTest, TabletopProtocolOptionsOutOfRangeAreRefusedByName) {
  const fs::path out = FreshDir("tabletop_bad");
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--layout diagonal", "--layout 'diagonal' does not exist; valid: paper, wide"},
      {"--demos 4,5",
       "--demos 5: the tabletop world records 2 demonstrations per scene "
       "configuration"},
      {"--noise -0.1", "--noise: must be a number from 0 to 0.5"},
      {"--noise nan", "--noise"},
      {"--demo-noise 3", "--demo-noise: must be a number from 0 to 1"},
      {"--observation depth", "--observation must be 'image'"},
      {"--random-shift 40", "--random-shift"},
      {"--random-erase 65", "--random-erase: must be a whole number from 0 to 64"},
      {"--observation state --random-erase 8",
       "--random-erase: the tabletop-state world's observations are vectors"},
      {"--action-chunk 0", "--action-chunk"},
      {"--beacon-weight -1", "--beacon-weight: must be a number from 0 to 1000"},
      {"--play-weight nan", "--play-weight: must be a number from 0 to 1000"},
      {"--feature-noise -0.5", "--feature-noise: must be a number from 0 to 10"},
      {"--feature-noise nan", "--feature-noise: must be a number from 0 to 10"},
      {"--feature-noise 11", "--feature-noise: must be a number from 0 to 10"},
      {"--feature-gate -1", "--feature-gate: must be a number from 0 to 100"},
      {"--feature-gate 1 --no-feature-gate", "excludes"},
      {"--ensemble half", "--ensemble: half not in {all,gripper}"},
      {"--feature-gate 1 --gate-target votes", "--gate-target: votes not in {loss,disagreement}"},
      {"--gate-target disagreement", "--gate-target: there is no feature gate to train"},
  };
  for (const auto& c : cases) {
    const CommandResult r = RunRecon(std::string("experiment tabletop --runs 1 --tests 1 ") +
                                     c.args + " --out " + (out / "x").string());
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
    EXPECT_FALSE(fs::exists(out / "x" / "summary.json")) << c.args;
  }
  // The wide layout has no configurations: an odd count is fine there (checked, not run).
  const CommandResult wide = RunRecon(
      "experiment tabletop --layout wide --runs 1 --tests 1 --demos 1 --steps 2 --baseline-steps 2 "
      "--image-size 32 --conditions baseline --gripper-min-std 0.2 --out " +
      (out / "wide").string());
  EXPECT_EQ(wide.exit_code, 0) << wide.output;
  // The gripper's floor is the last action's (u = six joint velocities, then the gripper).
  const nlohmann::json train = ReadJson(out / "wide" / "summary.json")["train"];
  EXPECT_EQ(train["action_min_std"], nlohmann::json({0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.2}));
}

// The gripper's floor names the worlds without a gripper command.
TEST(CellCliTest, AGripperFloorOutsideTheTabletopIsRefused) {
  const fs::path out = FreshDir("gripper_floor");
  for (const char* world : {"dynamic2d", "static2d", "bintransfer"}) {
    const CommandResult r =
        RunRecon(std::string("experiment ") + world +
                 " --runs 1 --tests 1 --gripper-min-std 0.1 --out " + (out / world).string());
    EXPECT_EQ(r.exit_code, 2) << world << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("--gripper-min-std: the " + std::string(world) +
                                    " world has no gripper command"));
    EXPECT_FALSE(fs::exists(out / world / "summary.json")) << world;
  }
}

// Shifting or erasing pixels of a vector world is refused before anything is written, so the
// corrected command runs into the same --out.
TEST(CellCliTest, ImageAugmentationOfVectorObservationsIsRefused) {
  const fs::path out = FreshDir("random_erase");
  for (const char* world : {"dynamic2d", "static2d", "bintransfer"}) {
    for (const std::string option : {"--random-erase 8", "--random-shift 4"}) {
      const std::string flag = option.substr(0, option.find(' '));
      const CommandResult r = RunRecon(std::string("experiment ") + world + " --runs 1 --tests 1 " +
                                       option + " --plan-only --out " + (out / world).string());
      EXPECT_EQ(r.exit_code, 2) << world << " " << option << ": " << r.output;
      EXPECT_THAT(r.output, HasSubstr(flag + ": the " + std::string(world) +
                                      " world's observations are vectors, not camera images"));
      EXPECT_FALSE(fs::exists(out / world)) << world << " " << option;
    }
    const CommandResult r = RunRecon(std::string("experiment ") + world +
                                     " --runs 1 --tests 1 --random-shift 0 --plan-only --out " +
                                     (out / world).string());
    EXPECT_EQ(r.exit_code, 0) << world << ": " << r.output;
    EXPECT_TRUE(fs::exists(out / world / "plan.json")) << world;
  }
}

// Who demonstrates: the scripted teacher or the simulated person; anything else, or the person
// on the true-positions diagnostic, is refused by name before anything is written.
TEST(CellCliTest, AnUnknownTeacherIsRefusedListingTheValidOnes) {
  const fs::path out = FreshDir("teacher");
  CommandResult r = RunRecon(
      "experiment tabletop --runs 1 --tests 1 --teacher robot --plan-only "
      "--out " +
      (out / "a").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--teacher must be one of expert, person; got 'robot'"));
  EXPECT_FALSE(fs::exists(out / "a"));
  r = RunRecon(
      "experiment tabletop --runs 1 --tests 1 --teacher person --observation state "
      "--plan-only --out " +
      (out / "b").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--teacher person"));
  EXPECT_FALSE(fs::exists(out / "b"));
  r = RunRecon(
      "experiment tabletop --runs 1 --tests 1 --teacher person --demo-noise 0.05 "
      "--plan-only --out " +
      (out / "d").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--demo-noise: the simulated person's takes"));
  EXPECT_FALSE(fs::exists(out / "d"));
  r = RunRecon(
      "experiment tabletop --runs 1 --tests 1 --teacher person --keep-pauses "
      "--plan-only --out " +
      (out / "c").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "c" / "plan.json"));
}

TEST(CellCliTest, TabletopImageSizeOutOfRangeIsRejected) {
  const CommandResult r = RunRecon("experiment tabletop --image-size 8");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--image-size"));
}

}  // namespace
