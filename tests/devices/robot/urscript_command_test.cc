// URScript lines: what the client formats, the fake parses back exactly; what is malformed (by
// hand or by mutation) is refused, counted by the fake and never moves it; and NaN is never sent.

#include "devices/robot/urscript_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "devices/robot/fake_ur_controller.h"
#include "engine/core/error.h"

namespace recon::robot {
namespace {

using ::testing::HasSubstr;

TEST(UrScriptCommandTest, FormattedLinesParseBackToTheSameNumbers) {
  const std::array<double, 6> qd = {0.1, -0.25, 1e-7, -3.14159265358979, 0, 2.0 / 3.0};
  const std::string line = FormatSpeedJ(qd, 1.4, 0.1);
  EXPECT_EQ(line.back(), '\n');
  EXPECT_EQ(line.rfind("speedj([0.1,-0.25,1e-07,", 0), 0u) << line;
  const auto parsed = ParseUrScriptLine(line);
  ASSERT_TRUE(parsed) << line;
  EXPECT_EQ(parsed->kind, UrScriptCommand::Kind::kSpeedJ);
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(parsed->velocity_rad_s[i], qd[i], 1e-11);
  EXPECT_DOUBLE_EQ(parsed->acceleration_rad_s2, 1.4);
  EXPECT_DOUBLE_EQ(parsed->time_s, 0.1);

  const auto stop = ParseUrScriptLine(FormatStopJ(2.0));
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->kind, UrScriptCommand::Kind::kStopJ);
  EXPECT_DOUBLE_EQ(stop->acceleration_rad_s2, 2.0);

  const auto tool = ParseUrScriptLine(FormatSetToolDigitalOut(0, true));
  ASSERT_TRUE(tool);
  EXPECT_EQ(tool->kind, UrScriptCommand::Kind::kSetToolDigitalOut);
  EXPECT_TRUE(tool->tool_value);
  EXPECT_FALSE(ParseUrScriptLine(FormatSetToolDigitalOut(1, false))->tool_value);

  // Spaces as a person would type them; t may be left out.
  const auto typed = ParseUrScriptLine(" speedj( [0, 0, 0, 0, 0, 0.5] , 1.0 )  ");
  ASSERT_TRUE(typed);
  EXPECT_EQ(typed->time_s, 0.0);
  EXPECT_EQ(typed->velocity_rad_s[5], 0.5);
}

TEST(UrScriptCommandTest, NonFiniteValuesAreNeverFormatted) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  try {
    FormatSpeedJ({0, 0, nan, 0, 0, 0}, 1.4, 0.1);
    FAIL() << "a NaN velocity was formatted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("joint 3"));
  }
  EXPECT_THROW(FormatSpeedJ({inf, 0, 0, 0, 0, 0}, 1.4, 0.1), UserError);
  EXPECT_THROW(FormatSpeedJ({}, nan, 0.1), UserError);
  EXPECT_THROW(FormatSpeedJ({}, 0, 0.1), UserError);
  EXPECT_THROW(FormatSpeedJ({}, 1.4, inf), UserError);
  EXPECT_THROW(FormatSpeedJ({}, 1.4, -1), UserError);
  EXPECT_THROW(FormatStopJ(nan), UserError);
  EXPECT_THROW(FormatSetToolDigitalOut(2, true), UserError);
}

TEST(UrScriptCommandTest, MalformedLinesAreRefused) {
  for (const char* line : {"",
                           "speedj",
                           "speedj()",
                           "speedj([0,0,0,0,0],1,0.1)",
                           "speedj([0,0,0,0,0,0,0],1,0.1)",
                           "speedj([0,0,0,0,0,0],0,0.1)",
                           "speedj([0,0,0,0,0,0],1,-0.1)",
                           "speedj([nan,0,0,0,0,0],1,0.1)",
                           "speedj([inf,0,0,0,0,0],1,0.1)",
                           "speedj([0x10,0,0,0,0,0],1,0.1)",
                           "speedj([0,0,0,0,0,0],1,0.1) extra",
                           "speedj([0,0,0,0,0,0],1,0.1",
                           "speedjx([0,0,0,0,0,0],1,0.1)",
                           "movej([0,0,0,0,0,0])",
                           "stopj()",
                           "stopj(-1)",
                           "stopj(a)",
                           "set_tool_digital_out(2,True)",
                           "set_tool_digital_out(0,true)",
                           "set_tool_digital_out(0.5,False)",
                           "popup(\"hi\")"}) {
    EXPECT_FALSE(ParseUrScriptLine(line)) << line;
  }
}

TEST(UrScriptCommandTest, TheFakeCountsMutatedLinesAsMalformedAndIgnoresThem) {
  constexpr uint64_t kSeed = 4242;
  std::printf("script line fuzz seed %llu\n", static_cast<unsigned long long>(kSeed));
  std::mt19937_64 rng(kSeed);
  FakeUrController::Options options;
  options.physics_rate_hz = 125;
  FakeUrController fake(options);
  const std::array<double, 6> home = fake.q_rad();
  const std::vector<std::string> valid = {FormatSpeedJ({0, 0, 0, 0, 0, 0}, 1.4, 0.1),
                                          FormatStopJ(2.0), FormatSetToolDigitalOut(1, false)};
  int64_t parsed = 0, refused = 0;
  const std::string alphabet = "speedjstopj([],.-+0123456789eE naTrueFls_\"\t\r";
  for (int n = 0; n < 20000; ++n) {
    std::string line = valid[rng() % valid.size()];
    line.pop_back();  // the newline
    for (int m = 1 + static_cast<int>(rng() % 3); m > 0; --m) {
      const size_t at = rng() % (line.size() + 1);
      switch (rng() % 3) {
        case 0:
          if (at < line.size()) line[at] = alphabet[rng() % alphabet.size()];
          break;
        case 1:
          line.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        default:
          line.erase(at, 1 + rng() % 3);
      }
    }
    const auto command = ParseUrScriptLine(line);
    if (command) {
      ++parsed;
      // Whatever parses is something a controller could run: finite and in range.
      for (double v : command->velocity_rad_s) ASSERT_TRUE(std::isfinite(v)) << line;
      ASSERT_TRUE(std::isfinite(command->acceleration_rad_s2)) << line;
      // A mutated speedj may carry any velocity: keep those away from the fake, which must stay
      // at home to show that nothing malformed moved it.
      if (command->kind == UrScriptCommand::Kind::kSpeedJ) continue;
    } else if (line.find_first_not_of(" \t\r") != std::string::npos) {
      ++refused;
    }
    fake.HandleScriptLine(line);
  }
  std::printf("%lld mutated lines parsed, %lld refused\n", static_cast<long long>(parsed),
              static_cast<long long>(refused));
  EXPECT_EQ(fake.malformed_lines(), refused);
  EXPECT_GT(refused, 10000);
  EXPECT_GT(parsed, 100);
  const std::array<double, 6> q = fake.q_rad();
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(q[i], home[i], 1e-9);
}

}  // namespace
}  // namespace recon::robot
