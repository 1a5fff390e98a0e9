// Every numeric option of `recon` fed the values a hostile or careless user types: each must be
// refused before anything runs, with exit 2, the option's name, and its range in plain numbers.
// Plus the check itself, value by value.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <limits>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/option_checks.h"
#include "app/cli/recon_app.h"
#include "tests/app/option_walk.h"
#include "tests/app/run_recon.h"

namespace recon::cli {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::RunRecon;

TEST(OptionChecksTest, ANumberMustBeFiniteInRangeAndWholeWhereAsked) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(CheckNumber("0.25", 0, 0.5, false, false), "");
  EXPECT_EQ(CheckNumber("0", 0, 0.5, false, false), "");
  EXPECT_EQ(CheckNumber("0.5", 0, 0.5, false, false), "");
  EXPECT_EQ(CheckNumber("7", 1, 100, true, false), "");
  EXPECT_EQ(CheckNumber("1e-9", 0, inf, false, true), "");
  EXPECT_EQ(CheckNumber(".25", 0, 0.5, false, false), "");
  EXPECT_EQ(CheckNumber("+2.5E-1", 0, 0.5, false, false), "");
  for (const char* bad : {"nan", "NaN",    "inf", "-inf",     "1e999", "",      "abc", "3x",
                          "0.6", "-0.1",   "0x0", " 0.1",     "0.1 ",  "0.1\n", "1e",  ".",
                          "-",   "0x1p-3", "1,5", "infinity", "0.1.2", "--0.1"}) {
    EXPECT_EQ(CheckNumber(bad, 0, 0.5, false, false),
              std::string("must be a number from 0 to 0.5 (got '") + bad + "')")
        << bad;
  }
  EXPECT_EQ(CheckNumber("0", 0, inf, false, true), "must be a number > 0 (got '0')");
  EXPECT_EQ(CheckNumber("2.5", 1, 2147483647, true, false),
            "must be a whole number from 1 to 2147483647 (got '2.5')");
  EXPECT_EQ(CheckNumber("0x10", 1, 100, true, false),
            "must be a whole number from 1 to 100 (got '0x10')");
  EXPECT_EQ(CheckNumber("99999999999", 1, 2147483647, true, false),
            "must be a whole number from 1 to 2147483647 (got '99999999999')");
}

struct OptionCase {
  std::string command;  ///< the command before the option, valid on its own
  std::string option;   ///< "" for a global option given as `command`
  bool whole;
};

// How ctest and gtest name a case: the command line it tries, not the struct's bytes.
void PrintTo(const OptionCase& c, std::ostream* os) { *os << c.command << c.option; }

fs::path OutDir() { return fs::path(::testing::TempDir()) / "recon_option_table"; }

// A run would start with any valid value, so a bad one must stop it first. Each command is
// valid on its own (or fails only later, at run time, on a missing file or device).
std::vector<OptionCase> NumericOptions() {
  const fs::path out = OutDir();
  const std::string train = "train --session " + (out / "missing").string() + " ";
  const std::string eval = "eval --session " + (out / "missing").string() + " ";
  const std::string record = "record --world static2d --session " + (out / "rec").string() + " ";
  const std::string repair = "session repair " + (out / "rep").string() + " --world dynamic2d ";
  const std::string split = "session split " + (out / "missing").string() + " ";
  const std::string render = "render --out " + (out / "render.png").string() + " ";
  const std::string calibrate = "calibrate --sim --out " + (out / "cal.json").string() + " ";
  const std::string camera = (out / "no_camera").string();
  const std::string info = "camera info --device " + camera + " ";
  const std::string grab =
      "camera grab --device " + camera + " --out " + (out / "grab.png").string() + " ";
  const std::string pose = "camera pose --device " + camera + " --calibration " +
                           (out / "c.yaml").string() + " --tags " + (out / "t.json").string() + " ";
  const std::string robot = "robot status --host 127.0.0.1 ";
  const std::string twin = "twin up " + (out / "twin").string() + " ";
  const std::string submit =
      "experiment submit " + (out / "missing_sweep").string() + " --slurm --dry-run ";
  std::vector<OptionCase> cases;
  for (const char* world : {"dynamic2d", "static2d", "bintransfer", "tabletop"}) {
    const std::string exp =
        std::string("experiment ") + world + " --out " + (out / "exp").string() + " ";
    for (const char* option :
         {"--demos", "--runs", "--tests", "--jobs", "--steps", "--baseline-steps", "--batch",
          "--play", "--feature-dim", "--random-shift", "--random-erase", "--action-chunk",
          "--beacon-filter", "--seed", "--policy-ensemble"}) {
      cases.push_back({exp, option, true});
    }
    for (const char* option :
         {"--lr", "--beacon-weight", "--play-weight", "--feature-noise", "--feature-gate",
          "--play-consistency", "--nll-min-std", "--gripper-min-std", "--weight-decay"}) {
      cases.push_back({exp, option, false});
    }
  }
  const std::string dynamic = "experiment dynamic2d --out " + (out / "exp").string() + " ";
  const std::string tabletop = "experiment tabletop --out " + (out / "exp").string() + " ";
  std::vector<OptionCase> rest = {
      {dynamic, "--noise", false},
      {tabletop, "--image-size", true},
      {tabletop, "--noise", false},
      {tabletop, "--demo-noise", false},
      {train, "--steps", true},
      {train, "--batch", true},
      {train, "--lr", false},
      {train, "--feature-dim", true},
      {train, "--seed", true},
      {train, "--action-chunk", true},
      {eval, "--tests", true},
      {eval, "--seed", true},
      {eval + "--probe ", "--grid", true},
      {eval + "--probe ", "--readout-scenes", true},
      {eval + "--saliency demo_0 ", "--frames", true},
      {submit, "--cpus-per-task", true},
      {submit, "--max-parallel", true},
      {record, "--demos", true},
      {record, "--play", true},
      {record, "--noise", false},
      {record, "--demo-noise", false},
      {record, "--image-size", true},
      {record, "--seed", true},
      {repair, "--noise", false},
      {repair, "--demo-noise", false},
      {repair, "--image-size", true},
      {repair, "--seed", true},
      {split, "--valid", false},
      {split, "--seed", true},
      {render, "--width", true},
      {render, "--height", true},
      {render, "--seed", true},
      {calibrate, "--points", true},
      {calibrate, "--seed", true},
      {calibrate, "--threshold", false},
      {calibrate, "--beacon-tag-id", true},
      {calibrate, "--beacon-tag-size", false},
      {calibrate, "--beacon-tag-height", false},
      {calibrate, "--frames", true},
      {calibrate, "--uwb-samples", true},
      {info, "--frames", true},
      {grab, "--count", true},
      {pose, "--min-tags", true},
      {robot, "--rtde-port", true},
      {robot, "--script-port", true},
      {robot, "--seconds", false},
      {twin, "--seed", true},
      {twin, "--seconds", false},
      {"devices list ", "--serial-timeout-ms", true},
      {"uwb monitor ", "--count", true},
      {"uwb monitor ", "--fake", true},
      {"uwb monitor ", "--seconds", false},
      {"--threads", "", true},
  };
  cases.insert(cases.end(), rest.begin(), rest.end());
  return cases;
}

// "experiment tabletop" from "experiment tabletop --out ... ": the subcommands before the flags.
std::string CommandPath(const std::string& command) {
  std::string path;
  size_t at = 0;
  while (at < command.size()) {
    const size_t end = std::min(command.find(' ', at), command.size());
    const std::string word = command.substr(at, end - at);
    if (word.empty() || word[0] == '-' || word.find('/') != std::string::npos) break;
    path += (path.empty() ? "" : " ") + word;
    at = end + 1;
  }
  return path;
}

// The table below must hold every numeric option `recon` has, so that a new option cannot
// skip the hostile values: the test walks the real command line (recon_app.h).
TEST(OptionTableTest, EveryNumericOptionIsRangeCheckedAndInTheTable) {
  CLI::App app;
  GlobalOptions global;
  BuildReconApp(app, global);
  std::set<std::pair<std::string, std::string>> table;
  for (const OptionCase& c : NumericOptions()) {
    table.insert(c.option.empty()
                     ? std::pair<std::string, std::string>{"", c.command}
                     : std::pair<std::string, std::string>{CommandPath(c.command), c.option});
  }
  size_t found = 0;
  const std::vector<std::string> gaps = testing::NumericOptionGaps(app, table, found);
  EXPECT_GT(found, 40u) << "the walk found too few options to be a walk of recon";
  EXPECT_TRUE(gaps.empty()) << "recon: " << ::testing::PrintToString(gaps);
}

class OptionTableTest : public ::testing::TestWithParam<OptionCase> {};

TEST_P(OptionTableTest, RefusesNanInfinityHugeNegativeAndText) {
  const OptionCase& c = GetParam();
  fs::create_directories(OutDir());
  for (const std::string& value : testing::HostileValues(c.whole)) {
    // --threads is a global option: it goes before a subcommand.
    const std::string args = c.option.empty()
                                 ? c.command + " " + value + " experiment tabletop --runs 1"
                                 : c.command + c.option + " " + value;
    const std::string name = c.option.empty() ? c.command : c.option;
    const CommandResult r = RunRecon(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(name + ": must be a ")) << args;
    EXPECT_THAT(r.output, HasSubstr("(got '" + value + "')")) << args;
    EXPECT_THAT(r.output, Not(HasSubstr("e+308"))) << args;
  }
  // Nothing ran, so nothing was written.
  for (const char* written :
       {"exp", "missing", "rec", "rep", "render.png", "cal.json", "grab.png"}) {
    EXPECT_FALSE(fs::exists(OutDir() / written)) << written;
  }
}

std::string CaseName(const ::testing::TestParamInfo<OptionCase>& info) {
  std::string name = info.param.option.empty()
                         ? info.param.command
                         : CommandPath(info.param.command) + "_" + info.param.option;
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Recon, OptionTableTest, ::testing::ValuesIn(NumericOptions()), CaseName);

}  // namespace
}  // namespace recon::cli
