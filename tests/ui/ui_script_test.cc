// The studio's input scripts are checked whole before anything runs: each bad line is refused
// with its file and line, and no screenshot can be written outside the screenshot folder.

#include "ui/testing/ui_script.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <string>

#include "engine/core/error.h"

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
      "wait 3\nsleep 1.5\nwait-idle\nwait-idle 30\nscreenshot shots/01_cell.png\r\n",
      "s.script");
  ASSERT_EQ(steps.size(), 9u);
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
}

TEST(UiScriptTest, ABadLineIsFoundBeforeTheFirstRunsAndNamed) {
  // Line 3 is bad: the error names it though lines 1-2 are fine (nothing has run yet).
  EXPECT_EQ(ErrorOf("wait 1\nclick Train\nwait -5\n").rfind("s.script:3: ", 0), 0u);
}

TEST(UiScriptTest, NumbersOutOfRangeOrMalformedAreRefused) {
  for (const char* line :
       {"wait -5", "wait 3abc", "wait 1.5", "wait 1e99", "wait", "wait nan", "wait 100001",
        "sleep 0", "sleep -1", "sleep inf", "sleep 1e400", "sleep 3601", "hold right -2",
        "hold right", "hold right 2s", "wait-idle 0", "wait-idle -3", "wait-idle soon"}) {
    const std::string error = ErrorOf(std::string(line) + "\n");
    EXPECT_EQ(error.rfind("s.script:1: ", 0), 0u) << line << " -> '" << error << "'";
  }
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

}  // namespace
}  // namespace recon::ui
