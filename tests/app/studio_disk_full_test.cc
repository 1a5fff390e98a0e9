// A full disk under the studio: the real recon-studio plays a short teaching session (the same
// as StudioFaultTest's) into a new session on a small file system of its own (SmallDisk), its
// home included, with the free space walking from nothing to just short of what a whole session
// writes, so the disk fills in a different step each time: the manifest, an episode, a
// checkpoint, a rollout, the report, the studio's own settings. After every run:
//   - the studio ended the script (exit 0) or stopped it at a blocked step (exit 2), never
//     crashed and never called the failure an internal error;
//   - the full disk was shown as "No space left on device", never with a temporary's name;
//   - no temporary is left, every file is whole, the session opens with nothing damaged.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "tests/app/saved_files.h"
#include "tests/app/small_disk.h"
#include "tests/app/studio_teaching_script.h"
#include "tests/app/walk_checks.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::FullDiskRun;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::SmallDisk;

TEST(StudioDiskFullTest, AFullDiskIsShownAndLeavesEverySavedFileWhole) {
  const fs::path root = fs::path("/tmp") / ("studio_disk_full_" + std::to_string(getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "extra");
  fs::create_directories(root / "work");
  std::ofstream(root / "extra" / "teach.script") << testing::kStudioTeachingScript;
  SmallDisk disk(/*session=*/"", root / "extra", root / "work",
                 std::string(testing::kStudioEnvironment) + RECON_STUDIO);
  const FullDiskRun roomy =
      disk.Run(testing::kStudioTeachingArgs, SmallDisk::kPlentyBytes / 2, "", "roomy_");
  ASSERT_EQ(roomy.result.exit_code, 0) << roomy.result.output;
  ASSERT_TRUE(fs::exists(roomy.root / "s" / "report")) << "the roomy run wrote no report";
  // What a whole session writes: everything but the inputs.
  const uint64_t written =
      testing::DirectoryBytes(roomy.root) - testing::DirectoryBytes(root / "extra");
  // And just short of the whole, where the rollouts' replays and the report are written last.
  const std::set<uint64_t> free_sizes = testing::FreeSizesToWalk(written, {512 << 10, 64 << 10});
  int shown = 0;
  for (const uint64_t free_bytes : free_sizes) {
    SCOPED_TRACE("the studio with " + std::to_string(free_bytes) + " bytes free (" +
                 std::to_string(written) + " written with room to spare)");
    const FullDiskRun run = disk.Run(testing::kStudioTeachingArgs, free_bytes);
    const CommandResult& r = run.result;
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.output;
    EXPECT_THAT(r.output, Not(HasSubstr("internal error")));
    EXPECT_THAT(r.output, Not(HasSubstr(".tmp.")));
    const size_t at = r.output.find("No space left on device");
    shown += at != std::string::npos;
    const size_t line = at == std::string::npos ? 0 : r.output.rfind('\n', at) + 1;
    std::printf(
        "%8llu bytes free: exit %d, %s\n", static_cast<unsigned long long>(free_bytes), r.exit_code,
        at == std::string::npos ? "no full disk met"
                                : r.output.substr(line, r.output.find('\n', at) - line).c_str());
    testing::ExpectEveryFileOldOrWhole(run.root, {}, root / "extra",
                                       /*temporaries_allowed=*/false);
    if (fs::exists(run.root / "s" / "session.json")) {
      testing::ExpectNoEpisodeDamaged(run.root / "s");
    }
    fs::remove_all(run.root);
  }
  // The walk must have reached the disk: with nothing free the session cannot even be created.
  std::printf("%d of %zu runs met the full disk and showed it\n", shown, free_sizes.size());
  EXPECT_GT(shown, 0) << "the full disk was never shown";
  fs::remove_all(root);
}

}  // namespace
}  // namespace recon
