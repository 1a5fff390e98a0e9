// The studio's input scripts are checked whole before anything runs: each bad line is refused
// with its file and line, and no screenshot can be written outside the screenshot folder.

#include "ui/testing/ui_script.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "ui/platform/frame_input.h"

namespace recon::ui {
namespace {

std::string ErrorOf(const std::string& script) {
  try {
    ParseUiScript(script, "s.script");
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(UiScriptTest, EveryCommandParsesWithItsArguments) {
  const std::vector<ScriptStep> steps = ParseUiScript(
      "# a comment\n\nclick Train Baseline and RECON\ntype 12\npress enter\nhold right 0.25\n"
      "wait 3\nsleep 1.5\nwait-idle\nwait-idle 30\nscreenshot shots/01_cell.png\r\n"
      "keyboard-take\nkeyboard-take 45\n",
      "s.script");
  ASSERT_EQ(steps.size(), 11u);
  EXPECT_EQ(steps[0].verb, ScriptStep::Verb::kClick);
  EXPECT_EQ(steps[0].text, "Train Baseline and RECON");
  EXPECT_EQ(steps[0].where, "s.script:3: ");
  EXPECT_EQ(steps[1].text, "12");
  EXPECT_EQ(steps[2].key, ImGuiKey_Enter);
  EXPECT_EQ(steps[3].key, ImGuiKey_RightArrow);
  EXPECT_DOUBLE_EQ(steps[3].seconds, 0.25);
  EXPECT_EQ(steps[4].frames, 3);
  EXPECT_DOUBLE_EQ(steps[5].seconds, 1.5);
  EXPECT_DOUBLE_EQ(steps[6].seconds, 600.0);
  EXPECT_DOUBLE_EQ(steps[7].seconds, 30.0);
  EXPECT_EQ(steps[8].verb, ScriptStep::Verb::kScreenshot);
  EXPECT_EQ(steps[8].text, "shots/01_cell.png");  // the Windows line end is not part of it
  EXPECT_EQ(steps[9].verb, ScriptStep::Verb::kKeyboardTake);
  EXPECT_DOUBLE_EQ(steps[9].seconds, 90.0);
  EXPECT_DOUBLE_EQ(steps[10].seconds, 45.0);
}

TEST(UiScriptTest, ABadLineIsFoundBeforeTheFirstRunsAndNamed) {
  // Line 3 is bad: the error names it though lines 1-2 are fine (nothing has run yet).
  EXPECT_EQ(ErrorOf("wait 1\nclick Train\nwait -5\n").rfind("s.script:3: ", 0), 0u);
}

TEST(UiScriptTest, NumbersOutOfRangeOrMalformedAreRefused) {
  for (const char* line : {"wait -5",
                           "wait 3abc",
                           "wait 1.5",
                           "wait 1e99",
                           "wait",
                           "wait nan",
                           "wait 100001",
                           "sleep 0",
                           "sleep -1",
                           "sleep inf",
                           "sleep 1e400",
                           "sleep 3601",
                           "hold right -2",
                           "hold right",
                           "hold right 2s",
                           "wait-idle 0",
                           "wait-idle -3",
                           "wait-idle soon",
                           "keyboard-take 0",
                           "keyboard-take -1",
                           "keyboard-take nan",
                           "keyboard-take 3601",
                           "person-takes",
                           "person-takes 4",
                           "person-takes 0 3",
                           "person-takes 101 3",
                           "person-takes 4 -1",
                           "person-takes 4 x",
                           "person-takes 4 3 5"}) {
    const std::string error = ErrorOf(std::string(line) + "\n");
    EXPECT_EQ(error.rfind("s.script:1: ", 0), 0u) << line << " -> '" << error << "'";
  }
}

TEST(UiScriptTest, PersonTakesParsesItsCountAndSeed) {
  const std::vector<ScriptStep> steps = ParseUiScript("person-takes 4 17\n", "s.script");
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].verb, ScriptStep::Verb::kPersonTakes);
  EXPECT_EQ(steps[0].frames, 4);
  EXPECT_EQ(steps[0].seed, 17u);
  EXPECT_NE(ErrorOf("person-takes 4\n").find("two numbers"), std::string::npos);
}

TEST(UiScriptTest, UnknownCommandsAndKeysAreRefusedListingTheValidOnes) {
  EXPECT_NE(ErrorOf("jump 3\n").find("click, type, press"), std::string::npos);
  EXPECT_NE(ErrorOf("press sideways\n").find("pagedown"), std::string::npos);
  EXPECT_NE(ErrorOf("hold sideways 1\n").find("unknown key 'sideways'"), std::string::npos);
  EXPECT_NE(ErrorOf("click\n").find("click needs"), std::string::npos);
}

TEST(UiScriptTest, AScreenshotCannotBeWrittenOutsideItsFolder) {
  EXPECT_NE(ErrorOf("screenshot /etc/cron.d/x.png\n").find("absolute"), std::string::npos);
  EXPECT_NE(ErrorOf("screenshot ../outside.png\n").find("'..'"), std::string::npos);
  EXPECT_NE(ErrorOf("screenshot a/../../outside.png\n").find("'..'"), std::string::npos);
  EXPECT_NE(ErrorOf("screenshot session.json\n").find(".png"), std::string::npos);
  EXPECT_NE(ErrorOf("screenshot\n").find("needs a file name"), std::string::npos);
  EXPECT_NO_THROW(ParseUiScript("screenshot a/b/c.png\n", "s.script"));
}

// Seeded random lines, valid and not: each either parses into a step whose numbers are finite
// and in range and whose screenshot stays inside its folder, or is refused with a UserError that
// names its line. Nothing else (another exception, a wrapped number, an escaping path) may come
// out of the parser, whatever a script holds.
TEST(UiScriptTest, RandomLinesParseInRangeOrAreRefusedNamingTheirLine) {
  constexpr uint32_t kSeed = 20261204;  // std::mt19937, so every CPU draws the same lines
  std::mt19937 rng(kSeed);
  const std::vector<std::string> verbs = {
      "click",      "type", "press", "hold",          "wait", "sleep",        "wait-idle",
      "screenshot", "Wait", "jump",  "keyboard-take", "",     "click\tTrain", "#click"};
  const std::vector<std::string> tokens = {"0",
                                           "-0",
                                           "1",
                                           "-1",
                                           "2.5",
                                           "1e3",
                                           "1e308",
                                           "1e999",
                                           "nan",
                                           "-nan",
                                           "inf",
                                           "0x10",
                                           "010",
                                           "+3",
                                           "3600",
                                           "3600.01",
                                           "3601",
                                           "100000",
                                           "100001",
                                           "2147483648",
                                           "99999999999999999999",
                                           "",
                                           " ",
                                           "up",
                                           "pageup",
                                           "sideways",
                                           "enter 1",
                                           "x.png",
                                           "a/b.png",
                                           "../x.png",
                                           "a/../../x.png",
                                           "/tmp/x.png",
                                           "x.PNG",
                                           "x.png/..",
                                           ".png",
                                           "Train##step",
                                           "\xff\xfe",
                                           std::string("a\0b", 3),
                                           "\x1b[2J"};
  std::uniform_int_distribution<size_t> pick_verb(0, verbs.size() - 1);
  std::uniform_int_distribution<size_t> pick_token(0, tokens.size() - 1);
  std::uniform_int_distribution<int> pick_count(0, 3);
  int parsed = 0;
  int refused = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string line = verbs[pick_verb(rng)];
    for (int t = pick_count(rng); t > 0; --t) line += " " + tokens[pick_token(rng)];
    SCOPED_TRACE("seed " + std::to_string(kSeed) + ", line " + std::to_string(i) + ": '" + line +
                 "'");
    std::vector<ScriptStep> steps;
    try {
      steps = ParseUiScript("# a comment\n" + line + "\n", "s.script");
    } catch (const UserError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("s.script:2: ", 0), 0u) << e.what();
      continue;
    }
    ++parsed;
    for (const ScriptStep& step : steps) {
      EXPECT_EQ(step.where, "s.script:2: ");
      EXPECT_TRUE(std::isfinite(step.seconds));
      EXPECT_GE(step.seconds, 0.0);
      EXPECT_LE(step.seconds, kMaxScriptSeconds);
      EXPECT_GE(step.frames, 0);
      EXPECT_LE(step.frames, kMaxScriptFrames);
      if (step.verb == ScriptStep::Verb::kHold || step.verb == ScriptStep::Verb::kSleep ||
          step.verb == ScriptStep::Verb::kWaitIdle ||
          step.verb == ScriptStep::Verb::kKeyboardTake) {
        EXPECT_GT(step.seconds, 0.0);
      }
      if (step.verb == ScriptStep::Verb::kPress || step.verb == ScriptStep::Verb::kHold) {
        EXPECT_GE(step.key, 0);
      }
      if (step.verb == ScriptStep::Verb::kClick) {
        EXPECT_FALSE(step.text.empty());
      }
      if (step.verb == ScriptStep::Verb::kScreenshot) {
        const std::filesystem::path path(step.text);
        EXPECT_FALSE(path.is_absolute());
        EXPECT_FALSE(path.has_root_directory());
        for (const std::filesystem::path& part : path) {
          EXPECT_NE(part, "..");
        }
      }
    }
  }
  // The draw reaches both sides, so neither branch's checks are vacuous.
  EXPECT_GT(parsed, 1000);
  EXPECT_GT(refused, 1000);
}

}  // namespace
}  // namespace recon::ui

namespace recon::ui {
namespace {

// The names people write for keys (xdotool's Return and Prior, a browser's ArrowUp), in any case.
TEST(UiScriptTest, KeyNamesAcceptTheUsualSynonymsInAnyCase) {
  EXPECT_EQ(ScriptKeyNamed("enter"), ImGuiKey_Enter);
  EXPECT_EQ(ScriptKeyNamed("Return"), ImGuiKey_Enter);
  EXPECT_EQ(ScriptKeyNamed("ESC"), ImGuiKey_Escape);
  EXPECT_EQ(ScriptKeyNamed("PgUp"), ImGuiKey_PageUp);
  EXPECT_EQ(ScriptKeyNamed("Prior"), ImGuiKey_PageUp);
  EXPECT_EQ(ScriptKeyNamed("next"), ImGuiKey_PageDown);
  EXPECT_EQ(ScriptKeyNamed("ArrowLeft"), ImGuiKey_LeftArrow);
  EXPECT_EQ(ScriptKeyNamed("kp_enter"), ImGuiKey_KeyPadEnter);
  EXPECT_EQ(ScriptKeyNamed("Delete"), ImGuiKey_Delete);
  EXPECT_EQ(ScriptKeyNamed("F12"), kEmergencyStopKey);
  EXPECT_EQ(ScriptKeyNamed("sideways"), -1);
  EXPECT_EQ(ScriptKeyNamed(""), -1);
  const std::vector<ScriptStep> steps = ParseUiScript("press return\nhold PageDown 0.5\n", "s");
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].key, ImGuiKey_Enter);
  EXPECT_EQ(steps[1].key, ImGuiKey_PageDown);
}

// The scripts the project ships (scripts/demo, scripts/person-sessions) parse whole, and the
// person's session asks for 4 kept takes, which scripts/person-sessions rewrites per seed.
TEST(UiScriptTest, TheShippedStudioScriptsParse) {
  const std::filesystem::path dir = std::filesystem::path(RECON_SOURCE_DIR) / "assets/studio";
  int scripts = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".script") continue;
    ++scripts;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<ScriptStep> steps;
    EXPECT_NO_THROW(steps = ParseUiScript(text, entry.path().string())) << entry.path();
    if (entry.path().filename() == "person_session.script") {
      int person_takes = 0;
      for (const ScriptStep& step : steps) {
        if (step.verb != ScriptStep::Verb::kPersonTakes) continue;
        ++person_takes;
        EXPECT_EQ(step.frames, 4);
        EXPECT_EQ(step.seed, 1u);
      }
      EXPECT_EQ(person_takes, 1);
    }
  }
  EXPECT_GE(scripts, 2);
}

}  // namespace
}  // namespace recon::ui
