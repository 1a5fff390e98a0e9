// Temporaries of killed writers: recognised by the writer's PID, removed only once it is dead;
// the check that an output folder is writable, from several threads at once; and reading whole
// files, which refuses what is not a regular file (a named pipe would block, a device never ends).

#include "engine/core/files.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/user_error_of.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using testing::UserErrorOf;

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

TEST(FilesTest, AWholeFileIsReadByteForByteAndAMissingOneIsNone) {
  const fs::path dir = Scratch();
  const std::string bytes("a\0b\nc", 5);
  std::ofstream(dir / "f.json", std::ios::binary) << bytes;
  EXPECT_EQ(ReadWholeFile((dir / "f.json").string()), bytes);
  EXPECT_EQ(ReadWholeFile((dir / "missing.json").string()), std::nullopt);
  fs::remove_all(dir);
}

TEST(FilesTest, ANamedPipeADeviceAndAFolderAreRefusedByName) {
  const fs::path dir = Scratch();
  const std::string pipe = (dir / "session.json").string();
  ASSERT_EQ(mkfifo(pipe.c_str(), 0644), 0);
  fs::create_directories(dir / "demo_0.h5");
  const std::string folder = (dir / "demo_0.h5").string();
  // Opening the pipe for reading would wait for a writer: the test ends only if it is refused.
  EXPECT_EQ(UserErrorOf([&] { ReadWholeFile(pipe); }),
            pipe + ": is a named pipe (FIFO), not a file");
  EXPECT_EQ(UserErrorOf([&] { RefuseNonRegularFile(pipe); }),
            pipe + ": is a named pipe (FIFO), not a file");
  EXPECT_EQ(UserErrorOf([] { ReadWholeFile("/dev/zero"); }), "/dev/zero: is a device, not a file");
  EXPECT_EQ(UserErrorOf([&] { ReadWholeFile(folder); }), folder + ": is a folder, not a file");
  // A symbolic link is followed: to a device it is refused, to a file it is read.
  fs::create_symlink("/dev/zero", dir / "zero.ckpt");
  fs::create_symlink(dir / "f", dir / "link.json");
  std::ofstream(dir / "f") << "{}";
  EXPECT_EQ(UserErrorOf([&] { RefuseNonRegularFile((dir / "zero.ckpt").string()); }),
            (dir / "zero.ckpt").string() + ": is a device, not a file");
  EXPECT_EQ(UserErrorOf([&] { RefuseNonRegularFile((dir / "link.json").string()); }), "");
  EXPECT_EQ(ReadWholeFile((dir / "link.json").string()), "{}");
  // A missing path is the caller's to name.
  EXPECT_EQ(UserErrorOf([&] { RefuseNonRegularFile((dir / "missing").string()); }), "");
  fs::remove_all(dir);
}

TEST(FilesTest, AFileOverTheLimitOfAWholeReadIsRefusedWithTheLimit) {
  const fs::path dir = Scratch();
  const std::string path = (dir / "plan.json").string();
  std::ofstream(path) << std::string(3 << 20, ' ');
  EXPECT_EQ(UserErrorOf([&] { ReadWholeFile(path, int64_t{2} << 20); }),
            path + ": is over 2 MiB, more than a file read whole may be");
  EXPECT_EQ(ReadWholeFile(path, int64_t{3} << 20)->size(), size_t{3} << 20);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon
