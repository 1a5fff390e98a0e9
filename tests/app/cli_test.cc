// Runs the real `recon` binary as a user would and checks exit codes, messages and files.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
using ::testing::Not;

using recon::testing::CommandResult;
using recon::testing::RunRecon;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("cli_" + name);
  fs::remove_all(dir);
  return dir;
}

// Tiny settings so an end-to-end run takes a few seconds.
const char* kTiny = "--runs 2 --tests 10 --demos 3 --steps 40 --baseline-steps 30";

TEST(CliTest, ShortExperimentWritesEverything) {
  const fs::path out = FreshDir("short");
  const CommandResult r = RunRecon(std::string("experiment dynamic2d ") + kTiny +
                                   " --conditions baseline,exact --seed 5 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("seed 5"));
  EXPECT_THAT(r.output, HasSubstr("exact"));
  EXPECT_THAT(r.output, HasSubstr("wrote " + (out / "dynamic2d.png").string()));
  std::ifstream in(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["conditions"]["exact"]["n"], 2);
  EXPECT_EQ(summary["conditions"]["baseline"]["train_steps"], 30);
  EXPECT_TRUE(fs::exists(out / "results.csv"));
}

TEST(CliTest, UnknownConditionIsAClearError) {
  const fs::path out = FreshDir("unknown");
  const CommandResult r = RunRecon(std::string("experiment dynamic2d ") + kTiny +
                                   " --conditions baseline,exakt --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("unknown condition 'exakt'"));
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

TEST(CliTest, ZeroDemosIsRejected) {
  const CommandResult r =
      RunRecon("experiment static2d --demos 0 --out " + FreshDir("zero").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--demos: must be a whole number from 1 to 10000 (got '0')"));
}

TEST(CliTest, TorchBackendRunsAndUnknownBackendIsRejected) {
  const fs::path out = FreshDir("torch");
  const CommandResult r = RunRecon(std::string("experiment dynamic2d ") + kTiny +
                                   " --conditions exact --backend torch --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(in)["train"]["backend"], "torch");
  const CommandResult bad = RunRecon(std::string("experiment dynamic2d ") + kTiny +
                                     " --backend tensorflow --out " + FreshDir("tf").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr("unknown backend 'tensorflow'"));
}

// LibTorch is loaded only by what needs it (torch_module.h): with the module unreachable, help
// and a Torch-free experiment still run, and a run on the Torch backend stops with an error that
// names the module's path and says what needs it.
TEST(CliTest, TorchIsLoadedOnlyByWhatNeedsIt) {
  const fs::path missing = FreshDir("no_module") / "librecon_torch.so";
  const std::string env = "RECON_TORCH_MODULE=" + missing.string() + " ";
  const CommandResult help = recon::testing::RunCommand(env + RECON_CLI + " --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  const fs::path out = FreshDir("no_module_run");
  const CommandResult plain =
      recon::testing::RunCommand(env + RECON_CLI + " experiment dynamic2d " + kTiny +
                                 " --conditions exact --out " + out.string());
  EXPECT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  const CommandResult torch = recon::testing::RunCommand(
      env + RECON_CLI + " experiment dynamic2d " + kTiny +
      " --conditions exact --backend torch --out " + FreshDir("no_module_torch").string());
  EXPECT_EQ(torch.exit_code, 2) << torch.output;
  EXPECT_THAT(torch.output, HasSubstr("cannot load the Torch module " + missing.string()));
  EXPECT_THAT(torch.output, HasSubstr("the Torch backend need it"));
  EXPECT_THAT(torch.output, Not(HasSubstr("internal error")));
}

// A crash says which signal and where, then ends the process as the signal would have: the
// log of a run that crashed once (on a user's machine, in CI) locates it. The crash is sent from
// outside, to a monitor that would otherwise run for a minute.
TEST(CliTest, ACrashIsReportedWithItsSignalAndStack) {
  const CommandResult r = recon::testing::RunCommand(
      std::string(RECON_CLI) + " uwb monitor --fake 1 --seconds 60 2>&1 & pid=$!; sleep 1; " +
      "kill -SEGV $pid; wait $pid");
  EXPECT_EQ(r.exit_code, 128 + 11) << r.output;
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // Under a sanitizer its own handler reports the crash (crash_report.cc steps aside).
  EXPECT_THAT(r.output, HasSubstr("Sanitizer")) << r.output;
  return;
#endif
  EXPECT_THAT(r.output, HasSubstr("recon: crashed (SEGV, Segmentation fault)")) << r.output;
  EXPECT_THAT(r.output, HasSubstr("the stack of the thread that crashed"));
  EXPECT_THAT(r.output, HasSubstr("recon(")) << "no frame of the program itself:\n" << r.output;
}

TEST(CliTest, AuthorsRecipeKeepsExplicitOptions) {
  const fs::path out = FreshDir("authors");
  const CommandResult r =
      RunRecon(std::string("experiment dynamic2d ") + kTiny +
               " --conditions exact --authors-recipe --lr 0.001 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "summary.json");
  const nlohmann::json train = nlohmann::json::parse(in)["train"];
  EXPECT_EQ(train["loss"], "mse-sample");                         // from the recipe
  EXPECT_EQ(train["weights"][1], 1.2);                            // from the recipe
  EXPECT_EQ(train["standardize_targets"], false);                 // from the recipe
  EXPECT_EQ(train["steps"], 40);                                  // typed: kTiny's --steps
  EXPECT_DOUBLE_EQ(train["learning_rate"].get<double>(), 0.001);  // typed
}

TEST(CliTest, NegativePlayIsRejected) {
  const CommandResult r =
      RunRecon("experiment static2d --play -3 --out " + FreshDir("play").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--play: must be a whole number from 0 to 100000 (got '-3')"));
}

TEST(CliTest, FeatureSizeNotAboveBeaconSizeIsRejected) {
  const CommandResult r =
      RunRecon(std::string("experiment dynamic2d ") + kTiny +
               " --conditions exact+other --feature-dim 4 --out " + FreshDir("k").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("k=4"));
}

TEST(CliTest, UnwritableOutputFolderFailsBeforeTraining) {
  const fs::path dir = FreshDir("unwritable");
  fs::create_directories(dir);
  std::ofstream(dir / "a_file") << "not a folder";
  const CommandResult r = RunRecon(std::string("experiment dynamic2d ") + kTiny + " --out " +
                                   (dir / "a_file" / "sub").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("a_file"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("training [")));
}

TEST(CliTest, ExistingResultsAreNotOverwrittenWithoutForce) {
  const fs::path out = FreshDir("existing");
  fs::create_directories(out);
  std::ofstream(out / "summary.json") << "{\"precious\": true}\n";
  const CommandResult r = RunRecon(std::string("experiment dynamic2d ") + kTiny +
                                   " --conditions exact --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--force"));
  std::ifstream in(out / "summary.json");
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "{\"precious\": true}\n");
}

TEST(CliTest, UnknownFlagAndMissingSubcommandAreUsageErrors) {
  EXPECT_EQ(RunRecon("experiment dynamic2d --no-such-flag").exit_code, 2);
  EXPECT_EQ(RunRecon("").exit_code, 2);
  EXPECT_EQ(RunRecon("experiment dynamic2d --runs abc").exit_code, 2);
  const CommandResult targets = RunRecon("experiment dynamic2d --targets meters");
  EXPECT_EQ(targets.exit_code, 2);
  EXPECT_THAT(targets.output, HasSubstr("--targets must be 'standardized' or 'raw'"));
  const CommandResult help = RunRecon("experiment dynamic2d --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.output, HasSubstr("--conditions"));
}

}  // namespace
