// The studio's saves under faults: the real recon-studio plays a short teaching session (mark the
// plate, calibrate, record a demonstration and play data, train both methods, roll out, write
// the report) into a new session with tests/support/fault_shim.c preloaded. A flush of a file,
// a flush of a folder or a rename fails with EIO at the first, middle or last call, or the studio
// is killed just after a rename. The studio shares the command line's writers; these tests hold
// its screens and jobs to the same rules: the failure is shown ("Input/output error", never a
// temporary's name) and never crashes the studio; every file is whole; the session opens with
// nothing damaged and no result claiming to be of a model it is not of.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "tests/app/fault_walk.h"
#include "tests/app/studio_teaching_script.h"

namespace recon {
namespace {

using testing::CommandResult;
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// Calls failed per kind: the first and the last flush of a file and of a folder; the first,
// middle and last rename (a whole session through the studio takes 10-20 s a run).
int StudioPoints(const std::string& kind) { return kind == "rename" ? 3 : 2; }

class StudioFaultTest : public testing::FaultWalkTest {
 protected:
  void SetUp() override {
    FaultWalkTest::SetUp();
    std::ofstream(root_ / "extra" / "teach.script") << testing::kStudioTeachingScript;
    program_ = std::string(testing::kStudioEnvironment) + RECON_STUDIO;
  }
  static constexpr const char* kArgs = testing::kStudioTeachingArgs;
};

TEST_F(StudioFaultTest, AFailingFlushOrRenameIsShownAndLeavesEverySavedFileWhole) {
  std::map<std::string, long> counts = CountCalls("", kArgs, "");
  ASSERT_GT(counts["rename"], 0);
  for (const std::string kind : {"fsync", "dirsync", "rename"}) {
    int shown = 0;
    for (const long call : testing::CallsToFail(counts[kind], StudioPoints(kind))) {
      SCOPED_TRACE("the studio with " + kind + " call " + std::to_string(call) + " of " +
                   std::to_string(counts[kind]) + " failing");
      fs::path run_root;
      const CommandResult r =
          Run("", kArgs, "", "RECON_FAULT=" + kind + ":" + std::to_string(call), &run_root);
      // A failed save is shown and the script goes on, or a later click finds its step blocked.
      ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.output;
      EXPECT_THAT(r.output, Not(HasSubstr("internal error")));
      EXPECT_THAT(r.output, Not(HasSubstr(".tmp.")));
      if (r.output.find("Input/output error") != std::string::npos) ++shown;
      ExpectEveryFileOldOrWhole(run_root, {}, /*temporaries_allowed=*/false);
      ExpectSessionWhole(run_root);
      fs::remove_all(run_root);
    }
    if (kind == "dirsync") {
      EXPECT_EQ(shown, 0) << "a folder's flush after a rename is not a failure";
    } else {
      EXPECT_GT(shown, 0) << "no failing " << kind << " was shown";
    }
  }
}

TEST_F(StudioFaultTest, KilledJustAfterARenameItLeavesAWholeSessionThatTheStudioContinues) {
  std::map<std::string, long> counts = CountCalls("", kArgs, "");
  for (const long call : testing::CallsToFail(counts["rename"], 2)) {
    SCOPED_TRACE("the studio killed after rename " + std::to_string(call) + " of " +
                 std::to_string(counts["rename"]));
    fs::path run_root;
    const CommandResult r = Run(
        "", kArgs, "",
        "RECON_FAULT=rename:" + std::to_string(call) + " RECON_FAULT_ACTION=kill-after", &run_root);
    ASSERT_TRUE(r.exit_code == 137 || r.exit_code == -1) << "exit " << r.exit_code << "\n"
                                                         << r.output;
    ExpectEveryFileOldOrWhole(run_root, {}, /*temporaries_allowed=*/true);
    ExpectSessionWhole(run_root);
    // The studio opens what was left and plays the session again from where it stands.
    const CommandResult again = RunAgain(run_root, kArgs);
    EXPECT_TRUE(again.exit_code == 0 || again.exit_code == 2) << again.output;
    EXPECT_THAT(again.output, Not(HasSubstr("internal error")));
    ExpectSessionWhole(run_root);
    fs::remove_all(run_root);
  }
}

}  // namespace
}  // namespace recon
