// Every numeric option of `recon-studio` fed the values a hostile or careless user types: each
// must be refused before the studio opens a window or a session, with exit 2, the option's name
// and its range. The table must cover every numeric option the real command line has.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/studio/studio_options.h"
#include "tests/app/option_walk.h"
#include "tests/support/run_command.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct StudioOptionCase {
  std::string option;
  bool whole;
};

void PrintTo(const StudioOptionCase& c, std::ostream* os) { *os << c.option; }

std::vector<StudioOptionCase> NumericOptions() {
  return {{"--seed", true},        {"--noise", false},        {"--demo-noise", false},
          {"--train-steps", true}, {"--rollout-tests", true}, {"--probe-grid", true},
          {"--frames", true},      {"--width", true},         {"--height", true},
          {"--countdown", false},  {"--ui-scale", false},     {"--calibration-points", true}};
}

TEST(StudioOptionTableTest, EveryNumericOptionIsRangeCheckedAndInTheTable) {
  CLI::App app;
  StudioFlags flags;
  AddStudioOptions(app, flags);
  std::set<std::pair<std::string, std::string>> table;
  for (const StudioOptionCase& c : NumericOptions()) table.insert({"", c.option});
  size_t found = 0;
  const std::vector<std::string> gaps = testing::NumericOptionGaps(app, table, found);
  EXPECT_GE(found, 8u);
  EXPECT_TRUE(gaps.empty()) << "recon-studio: " << ::testing::PrintToString(gaps);
}

class StudioOptionTable : public ::testing::TestWithParam<StudioOptionCase> {};

TEST_P(StudioOptionTable, RefusesNanInfinityHugeNegativeAndText) {
  const StudioOptionCase& c = GetParam();
  const fs::path session = fs::path(::testing::TempDir()) / "recon_studio_option_table";
  fs::remove_all(session);
  for (const std::string& value : testing::HostileValues(c.whole)) {
    const std::string args = std::string(RECON_STUDIO) + " --headless --session " +
                             session.string() + " " + c.option + " " + value;
    const testing::CommandResult r = testing::RunCommand(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.option + ": must be a ")) << args;
    EXPECT_THAT(r.output, HasSubstr("(got '" + value + "')")) << args;
    EXPECT_FALSE(fs::exists(session)) << args << ": nothing may be created";
  }
}

std::string CaseName(const ::testing::TestParamInfo<StudioOptionCase>& info) {
  std::string name = info.param.option.substr(2);
  for (char& ch : name) {
    if (ch == '-') ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Studio, StudioOptionTable, ::testing::ValuesIn(NumericOptions()),
                         CaseName);

}  // namespace
}  // namespace recon::studio
