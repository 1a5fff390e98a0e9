// Every numeric option of `recon` fed the values a hostile or careless user types: each must be
// refused before anything runs, with exit 2, the option's name, and its range in plain numbers.
// Plus the check itself, value by value.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "app/cli/option_checks.h"
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
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "1e999", "", "abc", "3x", "0.6", "-0.1"}) {
    EXPECT_EQ(CheckNumber(bad, 0, 0.5, false, false),
              std::string("must be a number from 0 to 0.5 (got '") + bad + "')")
        << bad;
  }
  EXPECT_EQ(CheckNumber("0", 0, inf, false, true), "must be a number > 0 (got '0')");
  EXPECT_EQ(CheckNumber("2.5", 1, 2147483647, true, false),
            "must be a whole number from 1 to 2147483647 (got '2.5')");
  EXPECT_EQ(CheckNumber("99999999999", 1, 2147483647, true, false),
            "must be a whole number from 1 to 2147483647 (got '99999999999')");
}

struct OptionCase {
  std::string command;  ///< the command before the option, valid on its own
  std::string option;   ///< "" for a global option given as `command`
  bool whole;
};

fs::path OutDir() { return fs::path(::testing::TempDir()) / "recon_option_table"; }

// A run would start with any valid value, so a bad one must stop it first.
std::vector<OptionCase> NumericOptions() {
  const fs::path out = OutDir();
  const std::string exp = "experiment tabletop --out " + (out / "exp").string() + " ";
  const std::string train = "train --session " + (out / "missing").string() + " ";
  const std::string record = "record --world static2d --session " + (out / "rec").string() + " ";
  const std::string repair = "session repair " + (out / "rep").string() + " --world dynamic2d ";
  return {
      {exp, "--demos", true},
      {exp, "--runs", true},
      {exp, "--tests", true},
      {exp, "--jobs", true},
      {exp, "--steps", true},
      {exp, "--baseline-steps", true},
      {exp, "--batch", true},
      {exp, "--play", true},
      {exp, "--feature-dim", true},
      {exp, "--random-shift", true},
      {exp, "--action-chunk", true},
      {exp, "--image-size", true},
      {exp, "--lr", false},
      {exp, "--beacon-weight", false},
      {exp, "--play-weight", false},
      {exp, "--feature-noise", false},
      {exp, "--feature-gate", false},
      {train, "--steps", true},
      {train, "--batch", true},
      {train, "--lr", false},
      {train, "--feature-dim", true},
      {record, "--demos", true},
      {record, "--play", true},
      {record, "--noise", false},
      {record, "--demo-noise", false},
      {record, "--image-size", true},
      {repair, "--noise", false},
      {repair, "--demo-noise", false},
      {repair, "--image-size", true},
      {"--threads", "", true},
  };
}

class OptionTableTest : public ::testing::TestWithParam<OptionCase> {};

TEST_P(OptionTableTest, RefusesNanInfinityHugeNegativeAndText) {
  const OptionCase& c = GetParam();
  fs::create_directories(OutDir());
  std::vector<std::string> bad = {"nan", "inf", "-1", "1e30", "abc"};
  if (c.whole) bad.push_back("2.5");
  for (const std::string& value : bad) {
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
  for (const char* written : {"exp", "missing", "rec", "rep"}) {
    EXPECT_FALSE(fs::exists(OutDir() / written)) << written;
  }
}

std::string CaseName(const ::testing::TestParamInfo<OptionCase>& info) {
  std::string name = info.param.command.substr(0, info.param.command.find(' ')) +
                     (info.param.option.empty() ? "" : "_" + info.param.option);
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Recon, OptionTableTest, ::testing::ValuesIn(NumericOptions()), CaseName);

}  // namespace
}  // namespace recon::cli
