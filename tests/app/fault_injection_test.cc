// A failing fsync or rename, for every command that writes (DiskFullTest covers the write itself).
// The real `recon` binary runs with tests/support/fault_shim.c preloaded: a first run counts the
// process's flushes of files, flushes of folders and renames, then each call in turn (or some
// spread over the run, CallsToFail) fails with EIO, as on a failing disk or a network file
// system, on a fresh copy of the session. After every run:
//   - a failed flush of a folder is not an error (it follows a rename that has happened): the
//     command succeeds;
//   - with a file's flush or a rename failing, the command succeeded, or it exited 2 saying
//     "Input/output error" about a file the user knows (never our temporary's or staging
//     folder's name), and never crashed; and such a failure is never ignored: some run fails;
//   - no temporary or staging folder is left;
//   - every file is either as it was or complete (HDF5 files pass their checksums, checkpoints
//     load, JSON parses, images, drawings, tables and pages end where they should);
//   - the session still opens and no episode reads as damaged.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/app/run_recon.h"
#include "tests/app/saved_files.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::CommandResult;
using ::testing::HasSubstr;
using testing::Incomplete;
using ::testing::Not;
using testing::ReadBytes;
using testing::RunCommand;
using testing::RunRecon;
using testing::Snapshot;

// File flushes and renames failed per command: all of them when there are at most this many,
// else this many spread from the first to the last (folder flushes: the first and the last).
constexpr int kMaxPoints = 5;

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

/// The calls of one kind to fail: 1..count, or `points` of them spread over it.
std::set<long> CallsToFail(long count, int points) {
  std::set<long> calls;
  if (count <= points) {
    for (long call = 1; call <= count; ++call) calls.insert(call);
  } else {
    for (int i = 0; i < points; ++i) calls.insert(1 + (count - 1) * i / (points - 1));
  }
  return calls;
}

class FaultInjectionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::path("/tmp") / ("fault_injection_test_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "extra");
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    work_ = root_ / test;
    fs::create_directories(work_);
  }

  /// Runs `recon args` on a fresh copy of `session` (at @S; @R is the copy's root, holding the
  /// suite's extra files at @R/extra) after the shell line `prepare`, with `fault_env` set.
  CommandResult Run(const fs::path& session, const std::string& args, const std::string& prepare,
                    const std::string& fault_env, fs::path* run_root) {
    *run_root = work_ / ("run_" + std::to_string(runs_++));
    fs::remove_all(*run_root);
    fs::create_directories(*run_root);
    fs::copy(session, *run_root / "s", fs::copy_options::recursive);
    fs::copy(root_ / "extra", *run_root / "extra", fs::copy_options::recursive);
    auto sub = [&](const std::string& text) {
      return Replace(Replace(text, "@S", (*run_root / "s").string()), "@R", run_root->string());
    };
    if (!prepare.empty()) {
      const CommandResult prepared = RunCommand(sub(prepare));
      EXPECT_EQ(prepared.exit_code, 0) << prepare << "\n" << prepared.output;
    }
    return RunCommand(fault_env + " LD_PRELOAD=" + RECON_FAULT_SHIM + " " + RECON_CLI + " " +
                      sub(args));
  }

  /// Counts the fsync and rename calls of `recon args` on a copy of `session`, then fails each
  /// (CallsToFail) in turn, checking the invariants above after every run.
  void WalkFaults(const fs::path& session, const std::string& args,
                  const std::string& prepare = "") {
    const std::map<std::string, std::string> before = Snapshot(session);
    const fs::path counts_file = work_ / "counts.txt";
    fs::remove(counts_file);
    fs::path counted_root;
    const CommandResult counted =
        Run(session, args, prepare, "RECON_FAULT_COUNTS=" + counts_file.string(), &counted_root);
    ASSERT_EQ(counted.exit_code, 0) << args << "\n" << counted.output;
    std::map<std::string, long> counts;
    {
      std::istringstream lines(ReadBytes(counts_file));
      std::string kind;
      long calls = 0;
      while (lines >> kind >> calls) counts[kind] = std::max(counts[kind], calls);
    }
    // Every command here saves something, so it must rename it into place.
    ASSERT_GT(counts["rename"], 0) << args << " wrote without a rename";
    for (const std::string kind : {"fsync", "dirsync", "rename"}) {
      int failures = 0;
      for (const long call : CallsToFail(counts[kind], kind == "dirsync" ? 2 : kMaxPoints)) {
        SCOPED_TRACE(args + " with " + kind + " call " + std::to_string(call) + " of " +
                     std::to_string(counts[kind]) + " failing");
        fs::path run_root;
        const CommandResult r = Run(session, args, prepare,
                                    "RECON_FAULT=" + kind + ":" + std::to_string(call), &run_root);
        ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.output;
        if (r.exit_code == 2) {
          ++failures;
          EXPECT_THAT(r.output, HasSubstr("Input/output error"));
          EXPECT_THAT(r.output, Not(HasSubstr(".tmp.")));
          EXPECT_THAT(r.output, Not(HasSubstr(".importing.")));
        }
        for (const auto& [name, bytes] : Snapshot(run_root)) {
          EXPECT_EQ(name.find(".tmp."), std::string::npos) << "a temporary was left: " << name;
          EXPECT_EQ(name.find(".partial"), std::string::npos) << "a temporary was left: " << name;
          EXPECT_EQ(name.find(".importing."), std::string::npos) << "a staging folder: " << name;
          const std::string in_session = name.rfind("s/", 0) == 0 ? name.substr(2) : "";
          const auto old = before.find(in_session);
          if (old != before.end() && old->second == bytes) continue;
          EXPECT_EQ(Incomplete(run_root / name), "") << name;
        }
        if (fs::exists(run_root / "s" / "session.json")) {
          const CommandResult info =
              RunRecon("session info " + (run_root / "s").string() + " --json");
          ASSERT_EQ(info.exit_code, 0) << info.output;
          const json summary = json::parse(info.output.substr(info.output.find('{')));
          EXPECT_TRUE(summary.value("damaged", json::array()).empty()) << info.output;
        }
        fs::remove_all(run_root);
      }
      if (kind == "dirsync") {
        // A folder is flushed after a rename into it has happened: nothing to undo or report.
        EXPECT_EQ(failures, 0) << args;
      } else if (counts[kind] > 0) {
        // A failed flush of a file or a failed rename is never ignored.
        EXPECT_GT(failures, 0) << args << ": no failing " << kind << " was reported";
      }
    }
  }

  // The sessions are made on first use (ctest runs each test in a process of its own).
  static fs::path Dynamic() {
    const fs::path dir = root_ / "dynamic2d";
    const std::string d = dir.string();
    if (!fs::exists(dir)) {
      MakeSession({"record --session " + d + " --world dynamic2d --demos 3 --play 4 --seed 3",
                   "train --session " + d + " --methods baseline,recon --steps 50",
                   "eval --session " + d + " --tests 3",
                   "session export " + d + " --out " + (root_ / "extra" / "export.hdf5").string()});
    }
    return dir;
  }
  static fs::path Tabletop() {
    const fs::path dir = root_ / "tabletop";
    const std::string d = dir.string();
    if (!fs::exists(dir)) {
      MakeSession({"record --session " + d + " --world tabletop --demos 2 --play 2 --seed 2",
                   "train --session " + d + " --methods baseline --steps 20"});
    }
    return dir;
  }
  static void MakeSession(const std::vector<std::string>& lines) {
    for (const std::string& line : lines) {
      const CommandResult r = RunRecon(line);
      ASSERT_EQ(r.exit_code, 0) << line << "\n" << r.output;
    }
  }

  static fs::path root_;
  fs::path work_;
  int runs_ = 0;
};

fs::path FaultInjectionTest::root_;

// The shim itself: a mistyped setting would inject nothing and let the walks above pass for the
// wrong reason, so it stops the program instead.
TEST_F(FaultInjectionTest, AMistypedFaultSettingStopsTheProgram) {
  for (const std::string setting : {"fsnyc:1", "fsync", "rename:0", "rename:2x", "dirsync:-1"}) {
    const CommandResult r = RunCommand(
        "RECON_FAULT=" + setting + " LD_PRELOAD=" + RECON_FAULT_SHIM + " " + RECON_CLI + " --help");
    EXPECT_EQ(r.exit_code, 97) << setting << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("is not fsync:N, dirsync:N or rename:N")) << setting;
  }
  const CommandResult valid = RunCommand(std::string("RECON_FAULT=fsync:1 LD_PRELOAD=") +
                                         RECON_FAULT_SHIM + " " + RECON_CLI + " --help");
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
}

TEST_F(FaultInjectionTest, RecordingMoreDemonstrations) {
  WalkFaults(Dynamic(), "record --session @S --demos 2 --play 2");
}

TEST_F(FaultInjectionTest, RecordingCameraEpisodes) {
  WalkFaults(Tabletop(), "record --session @S --demos 2 --play 2");
}

TEST_F(FaultInjectionTest, Training) {
  WalkFaults(Dynamic(), "train --session @S --methods baseline,recon --steps 50");
}

TEST_F(FaultInjectionTest, EvaluatingWithReplays) {
  WalkFaults(Tabletop(), "eval --session @S --tests 1");
}

TEST_F(FaultInjectionTest, TheReport) { WalkFaults(Dynamic(), "report @S"); }

TEST_F(FaultInjectionTest, Export) { WalkFaults(Dynamic(), "session export @S --out @R/out.hdf5"); }

TEST_F(FaultInjectionTest, Import) {
  WalkFaults(Dynamic(), "session import @R/extra/export.hdf5 --session @R/imported");
}

TEST_F(FaultInjectionTest, MarkingAnEpisode) {
  WalkFaults(Dynamic(), "session mark @S demo_1 --bad --note \"fell over\"");
}

TEST_F(FaultInjectionTest, DeletingAnEpisode) {
  WalkFaults(Dynamic(), "session delete-episode @S demo_1");
}

TEST_F(FaultInjectionTest, DrawingAValidationSplit) {
  WalkFaults(Dynamic(), "session split @S --valid 0.34 --seed 2");
}

TEST_F(FaultInjectionTest, RepairingALostManifest) {
  WalkFaults(Dynamic(), "session repair @S --world dynamic2d --seed 3", "rm @S/session.json");
}

TEST_F(FaultInjectionTest, Calibration) {
  WalkFaults(Dynamic(), "calibrate --sim --points 6 --out @R/calibration.json");
}

TEST_F(FaultInjectionTest, RenderingAnImage) {
  WalkFaults(Dynamic(), "render --width 64 --height 48 --out @R/top.png");
}

TEST_F(FaultInjectionTest, AnExperimentsResults) {
  WalkFaults(Dynamic(),
             "experiment static2d --demos 2 --runs 1 --steps 30 --baseline-steps 30 --tests 2 "
             "--jobs 1 --out @R/exp");
}

}  // namespace
}  // namespace recon
