#pragma once

// What every fault walk of the real binaries (DiskFullTest, FaultInjectionTest, KillAtWriteTest,
// StudioFaultTest) starts from and checks after each run: the sessions it copies, made once per
// test process by the real `recon`, and the state a run may leave.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/app/run_recon.h"
#include "tests/app/saved_files.h"

namespace recon::testing {

/// Runs each `recon` command line; each must succeed.
inline void MakeSession(const std::vector<std::string>& lines) {
  for (const std::string& line : lines) {
    const CommandResult r = RunRecon(line);
    ASSERT_EQ(r.exit_code, 0) << line << "\n" << r.output;
  }
}

/// A Dynamic 2D session at ROOT/dynamic2d (demonstrations, play data, both methods trained and
/// rolled out), and its export at ROOT/extra/export.hdf5; made on first use (ctest runs each
/// test in a process of its own).
inline std::filesystem::path DynamicWalkSession(const std::filesystem::path& root) {
  const std::filesystem::path dir = root / "dynamic2d";
  const std::string d = dir.string();
  if (!std::filesystem::exists(dir)) {
    MakeSession({"record --session " + d + " --world dynamic2d --demos 3 --play 4 --seed 3",
                 "train --session " + d + " --methods baseline,recon --steps 50",
                 "eval --session " + d + " --tests 3",
                 "session export " + d + " --out " + (root / "extra" / "export.hdf5").string()});
  }
  return dir;
}

/// A tabletop session with camera episodes at ROOT/tabletop, the Baseline trained.
inline std::filesystem::path TabletopWalkSession(const std::filesystem::path& root) {
  const std::filesystem::path dir = root / "tabletop";
  const std::string d = dir.string();
  if (!std::filesystem::exists(dir)) {
    MakeSession({"record --session " + d + " --world tabletop --demos 2 --play 2 --seed 2",
                 "train --session " + d + " --methods baseline --steps 20"});
  }
  return dir;
}

/// What a run may leave in `run_root` (a session's copy at s/, the inputs at extra/): each file
/// as it was in `before` (the session's files, by path inside it) or complete, the inputs as
/// `inputs` holds them. Temporaries are reported unless `temporaries_allowed`.
inline void ExpectEveryFileOldOrWhole(const std::filesystem::path& run_root,
                                      const std::map<std::string, std::string>& before,
                                      const std::filesystem::path& inputs,
                                      bool temporaries_allowed) {
  for (const auto& [name, bytes] : Snapshot(run_root)) {
    const bool temporary = name.find(".tmp.") != std::string::npos ||
                           name.find(".partial") != std::string::npos ||
                           name.find(".importing.") != std::string::npos;
    if (temporary) {
      EXPECT_TRUE(temporaries_allowed) << "a temporary was left: " << name;
      continue;
    }
    if (name.rfind("extra/", 0) == 0) {
      EXPECT_EQ(bytes, ReadBytes(inputs / name.substr(6))) << "an input was changed: " << name;
      continue;
    }
    const std::string in_session = name.rfind("s/", 0) == 0 ? name.substr(2) : "";
    const auto old = before.find(in_session);
    if (old != before.end() && old->second == bytes) continue;
    EXPECT_EQ(Incomplete(run_root / name), "") << name;
  }
}

/// `session info --json` of `session`, which must succeed and list no damaged episode; null when
/// it did not.
inline nlohmann::json ExpectNoEpisodeDamaged(const std::filesystem::path& session) {
  const CommandResult info = RunRecon("session info " + session.string() + " --json");
  EXPECT_EQ(info.exit_code, 0) << info.output;
  if (info.exit_code != 0) return nullptr;
  const nlohmann::json summary = nlohmann::json::parse(info.output.substr(info.output.find('{')));
  EXPECT_TRUE(summary.value("damaged", nlohmann::json::array()).empty()) << info.output;
  return summary;
}

}  // namespace recon::testing
