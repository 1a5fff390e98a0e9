// Temporaries of killed writers: recognised by the writer's PID, removed only once it is dead;
// and the check that an output folder is writable, from several threads at once.

#include "engine/core/files.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace recon {
namespace {

namespace fs = std::filesystem;

/// The PID of a process that has exited (a child that was reaped).
pid_t DeadPid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return child;
}

fs::path Scratch() {
  const fs::path dir = fs::path(::testing::TempDir()) / ("files_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void Touch(const fs::path& path) { std::ofstream(path) << "x"; }

TEST(FilesTest, ATemporaryIsGarbageOnlyOnceItsWriterIsDead) {
  const std::string dead = std::to_string(DeadPid());
  EXPECT_TRUE(IsTemporaryOfDeadWriter("baseline.ckpt.tmp." + dead));
  EXPECT_FALSE(IsTemporaryOfDeadWriter("baseline.ckpt.tmp." + std::to_string(getpid())));
  for (const char* not_temporary :
       {"demo_0.h5", "x.tmp.", "x.tmp.12a", "x.tmp.-4", "tmp.5", "x.tmp.12345678901"}) {
    EXPECT_FALSE(IsTemporaryOfDeadWriter(not_temporary)) << not_temporary;
  }
}

TEST(FilesTest, RemovingDeadTemporariesKeepsLiveOnesAndEverythingElse) {
  const fs::path dir = Scratch();
  const std::string dead = std::to_string(DeadPid()), live = std::to_string(getpid());
  Touch(dir / ("a.json.tmp." + dead));
  Touch(dir / ("b.png.tmp." + dead));
  Touch(dir / ("a.json.tmp." + live));
  Touch(dir / "a.json");
  EXPECT_EQ(RemoveDeadTemporariesIn(dir.string(), "a.json.tmp."), 1);
  EXPECT_TRUE(fs::exists(dir / ("b.png.tmp." + dead)));  // another target's
  EXPECT_EQ(RemoveDeadTemporariesIn(dir.string()), 1);
  EXPECT_TRUE(fs::exists(dir / ("a.json.tmp." + live)));
  EXPECT_TRUE(fs::exists(dir / "a.json"));
  EXPECT_EQ(RemoveDeadTemporariesIn((dir / "missing").string()), 0);
  fs::remove_all(dir);
}

TEST(FilesTest, WritingAFileRemovesWhatAKilledWriterOfItLeft) {
  const fs::path dir = Scratch();
  const fs::path target = dir / "calibration.json";
  const fs::path left = dir / ("calibration.json.tmp." + std::to_string(DeadPid()));
  Touch(left);
  WriteFileAtomically(target.string(), "{}\n");
  EXPECT_FALSE(fs::exists(left));
  EXPECT_TRUE(fs::exists(target));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(FilesTest, StagingFoldersOfDeadImportsAreRemovedWithTheirContents) {
  const fs::path dir = Scratch();
  const std::string dead = std::to_string(DeadPid()), live = std::to_string(getpid());
  for (const std::string& name : {"copy.importing." + dead, "copy.importing." + live,
                                  "other.importing." + dead, std::string("copy.importing.x")}) {
    fs::create_directories(dir / name / "episodes");
    Touch(dir / name / "episodes" / "demo_0.h5");
  }
  EXPECT_EQ(RemoveDeadStagingFoldersOf((dir / "copy").string(), ".importing."), 1);
  EXPECT_FALSE(fs::exists(dir / ("copy.importing." + dead)));
  EXPECT_TRUE(fs::exists(dir / ("copy.importing." + live) / "episodes" / "demo_0.h5"));
  EXPECT_TRUE(fs::exists(dir / ("other.importing." + dead)));
  EXPECT_TRUE(fs::exists(dir / "copy.importing.x"));
  EXPECT_TRUE(IsTemporaryOfDeadWriter("copy.importing." + dead, ".importing."));
  EXPECT_FALSE(IsTemporaryOfDeadWriter("copy.importing." + dead));  // not a ".tmp." file
  fs::remove_all(dir);
}

TEST(FilesTest, ThreadsCheckTheSameOutputFolderAtOnce) {
  // Methods trained side by side each make sure training/ is writable, at the same moment.
  const fs::path dir = Scratch() / "training";
  constexpr int kThreads = 8, kRounds = 200;
  std::vector<int> failures(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < kRounds; ++i) {
        try {
          EnsureWritableDirectory(dir.string());
        } catch (const std::exception&) {
          ++failures[t];
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(failures[t], 0) << "thread " << t;
  EXPECT_TRUE(fs::is_empty(dir)) << "a write probe was left behind";
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace recon
