#pragma once

// The fault walks of the real `recon` binary, shared by FaultInjectionTest (a failing fsync or
// rename at each call) and KillAtWriteTest (kill -9 at exact points of a write). The binary runs
// with tests/support/fault_shim.c preloaded on a fresh copy of a session for every fault.

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

#include "engine/core/digest.h"
#include "tests/app/run_recon.h"
#include "tests/app/saved_files.h"
#include "tests/app/walk_checks.h"

namespace recon::testing {

namespace fs = std::filesystem;
using json = nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

// File flushes and renames failed per command: all of them when there are at most this many,
// else this many spread from the first to the last (folder flushes: the first and the last).
constexpr int kMaxPoints = 5;
// Calls of each kind a kill -9 lands on: the first, the middle and the last.
constexpr int kKillPoints = 3;

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

class FaultWalkTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::path("/tmp") / ("fault_walk_test_" + std::to_string(getpid()));
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
    if (!session.empty()) fs::copy(session, *run_root / "s", fs::copy_options::recursive);
    fs::copy(root_ / "extra", *run_root / "extra", fs::copy_options::recursive);
    if (!prepare.empty()) {
      const CommandResult prepared = RunCommand(Substitute(prepare, *run_root));
      EXPECT_EQ(prepared.exit_code, 0) << prepare << "\n" << prepared.output;
    }
    return RunCommand(fault_env + " LD_PRELOAD=" + RECON_FAULT_SHIM + " " +
                      Substitute(program_ + " " + args, *run_root));
  }

  /// Runs `recon args` again in `run_root` as it was left, without faults.
  CommandResult RunAgain(const fs::path& run_root, const std::string& args) const {
    return RunCommand(Substitute(program_ + " " + args, run_root));
  }

  /// `text` with @S for the session copy in `run_root` and @R for `run_root`.
  static std::string Substitute(const std::string& text, const fs::path& run_root) {
    return Replace(Replace(text, "@S", (run_root / "s").string()), "@R", run_root.string());
  }

  /// The fsync, dirsync and rename calls of one whole run of `recon args` on a copy of `session`.
  std::map<std::string, long> CountCalls(const fs::path& session, const std::string& args,
                                         const std::string& prepare) {
    const fs::path counts_file = work_ / "counts.txt";
    fs::remove(counts_file);
    fs::path counted_root;
    const CommandResult counted =
        Run(session, args, prepare, "RECON_FAULT_COUNTS=" + counts_file.string(), &counted_root);
    EXPECT_EQ(counted.exit_code, 0) << args << "\n" << counted.output;
    std::map<std::string, long> counts;
    std::istringstream lines(ReadBytes(counts_file));
    std::string kind;
    long calls = 0;
    while (lines >> kind >> calls) counts[kind] = std::max(counts[kind], calls);
    fs::remove_all(counted_root);
    return counts;
  }

  /// What a run may leave behind (walk_checks.h), the suite's inputs unchanged.
  static void ExpectEveryFileOldOrWhole(const fs::path& run_root,
                                        const std::map<std::string, std::string>& before,
                                        bool temporaries_allowed) {
    testing::ExpectEveryFileOldOrWhole(run_root, before, root_ / "extra", temporaries_allowed);
  }

  /// The session in `run_root`, if it has a manifest, opens and has no damaged episode; and no
  /// training record or rollouts of a method claim to be current while its checkpoint holds
  /// another model than the one they name (a save of several files cut between them).
  static void ExpectSessionWhole(const fs::path& run_root) {
    if (!fs::exists(run_root / "s" / "session.json")) return;
    const json summary = ExpectNoEpisodeDamaged(run_root / "s");
    for (const char* kind : {"training", "rollouts"}) {
      if (!summary.contains(kind) || !summary[kind].is_object()) continue;
      for (const auto& [method, record] : summary[kind].items()) {
        const fs::path checkpoint = run_root / "s" / "checkpoints" / (method + ".ckpt");
        const std::string id = fs::exists(checkpoint)
                                   ? "fnv1a:" + DigestHex(Fnv1a(ReadBytes(checkpoint)))
                                   : "(no checkpoint)";
        if (record.value("model_id", json(nullptr)) != json(id)) {
          EXPECT_FALSE(record.value("out_of_date", json(nullptr)).is_null())
              << kind << "/" << method << ".json is of another model than " << checkpoint
              << " and is not shown as out of date";
        }
      }
    }
  }

  /// kill -9 at exact points of `recon args` on copies of `session`: just before a file's flush
  /// (its temporary written, not yet renamed) and just after a rename (one file of several in
  /// place), at kKillPoints calls of each spread over the run. After each kill every file is
  /// the old one or whole (temporaries of the dead process may remain) and the session opens
  /// with nothing damaged; the same command run again then ends with exit 0 or a clear error
  /// (2), and when it succeeds no temporary of the killed run is left.
  void WalkKills(const fs::path& session, const std::string& args,
                 const std::string& prepare = "") {
    const std::map<std::string, std::string> before = Snapshot(session);
    std::map<std::string, long> counts = CountCalls(session, args, prepare);
    ASSERT_GT(counts["rename"], 0) << args << " wrote without a rename";
    int kills = 0;
    for (const auto& [kind, action] :
         {std::pair<std::string, std::string>{"fsync", "kill-before"}, {"rename", "kill-after"}}) {
      for (const long call : CallsToFail(counts[kind], kKillPoints)) {
        SCOPED_TRACE(args + " killed " + (action == "kill-before" ? "before" : "after") + " " +
                     kind + " call " + std::to_string(call) + " of " +
                     std::to_string(counts[kind]));
        fs::path run_root;
        const CommandResult r = Run(
            session, args, prepare,
            "RECON_FAULT=" + kind + ":" + std::to_string(call) + " RECON_FAULT_ACTION=" + action,
            &run_root);
        // Killed by the signal: the shell reports 128 + 9, or the status is not an exit at all.
        ASSERT_TRUE(r.exit_code == 137 || r.exit_code == -1) << "exit " << r.exit_code << "\n"
                                                             << r.output;
        ++kills;
        ExpectEveryFileOldOrWhole(run_root, before, /*temporaries_allowed=*/true);
        ExpectSessionWhole(run_root);
        const CommandResult again = RunAgain(run_root, args);
        EXPECT_TRUE(again.exit_code == 0 || again.exit_code == 2) << again.output;
        if (again.exit_code == 0) ExpectEveryFileOldOrWhole(run_root, before, false);
        ExpectSessionWhole(run_root);
        fs::remove_all(run_root);
      }
    }
    EXPECT_GT(kills, 0);
  }

  /// Counts the fsync and rename calls of `recon args` on a copy of `session`, then fails each
  /// (CallsToFail) in turn, checking the invariants above after every run.
  void WalkFaults(const fs::path& session, const std::string& args,
                  const std::string& prepare = "") {
    const std::map<std::string, std::string> before = Snapshot(session);
    std::map<std::string, long> counts = CountCalls(session, args, prepare);
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
        ExpectEveryFileOldOrWhole(run_root, before, /*temporaries_allowed=*/false);
        ExpectSessionWhole(run_root);
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

  static fs::path Dynamic() { return DynamicWalkSession(root_); }
  static fs::path Tabletop() { return TabletopWalkSession(root_); }

  static inline fs::path root_;
  /// The command line run (with @S and @R substituted): `recon` unless a test says otherwise.
  std::string program_ = RECON_CLI;
  fs::path work_;
  int runs_ = 0;
};

}  // namespace recon::testing
