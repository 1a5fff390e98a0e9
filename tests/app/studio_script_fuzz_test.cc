// The studio's scripts fuzzed through the real recon-studio binary: seeded random scripts, made
// of the studio's own buttons, keys, typing, waits and screenshots (and, in some, one line the
// parser must refuse), are played headless into a new session. Whatever a script does, the
// studio ends with exit 0 or a clear error naming the script's line (2), never a crash or an
// internal error; the session it leaves opens with every episode, checkpoint, record and figure
// whole; and nothing is written outside the session, the screenshot folder and the studio's own
// list of recent sessions.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/store/session.h"
#include "tests/app/saved_files.h"
#include "tests/support/run_command.h"

namespace recon {
namespace {

namespace fs = std::filesystem;

// What a teacher can click in the studio (the sidebar's steps, each screen's buttons, the
// camera's objects, the teleop choices, the episode list's rows), plus labels that are not
// there. The session picker is left out: what it opens is the folder a user typed, anywhere.
const std::vector<std::string> kLabels = {"Cell##step",
                                          "Beacons##step",
                                          "Calibrate##step",
                                          "Record##step",
                                          "Play data##step",
                                          "Train##step",
                                          "Rollouts##step",
                                          "Report##step",
                                          "object:plate",
                                          "object:bowl",
                                          "object:toast",
                                          "plate",
                                          "bowl",
                                          "Collect points and fit",
                                          "Calibrate again",
                                          "Cancel##calibration",
                                          "Start recording",
                                          "Stop and keep",
                                          "Discard",
                                          "[ ] Keyboard##teleop",
                                          "[ ] Scripted##teleop",
                                          "[ ] Gamepad##teleop",
                                          "Bad##demo_0",
                                          "Good##demo_0",
                                          "Delete##demo_1",
                                          "Re-record##demo_0",
                                          "Record 30 play samples",
                                          "Stop",
                                          "Train Baseline and RECON",
                                          "Cancel training",
                                          "Run rollouts",
                                          "Scene >",
                                          "< Scene",
                                          "|<",
                                          ">|",
                                          ">##step",
                                          "<##step-back",
                                          "Play",
                                          "Pause",
                                          "Write the report",
                                          "Rescan",
                                          "E-STOP (F12)",
                                          "Release e-stop",
                                          "Dismiss",
                                          "Recrod##step"};
const std::vector<std::string> kKeys = {"enter",    "tab",  "escape", "backspace", "space",
                                        "up",       "down", "left",   "right",     "pageup",
                                        "pagedown", "f12",  "Return", "esc"};
// Lines the parser refuses, each for a different reason.
const std::vector<std::string> kBadLines = {"wait -1",
                                            "wait nan",
                                            "wait 100001",
                                            "sleep 0",
                                            "sleep inf",
                                            "sleep 3601",
                                            "hold up",
                                            "hold sideways 0.2",
                                            "press",
                                            "press sideways",
                                            "click",
                                            "screenshot ../out.png",
                                            "screenshot /tmp/out.png",
                                            "screenshot shot.jpg",
                                            "screenshot",
                                            "jump 3",
                                            "wait-idle -5",
                                            "wait 1e999",
                                            "\x01\x02 garbage"};

struct FuzzScript {
  std::string text;
  int first_bad_line = 0;  ///< 0 when every line parses
};

// A teaching session's clicks in the workflow's order (assets/studio/full_session.script,
// shortened). A script walks through them with random lines between, so it gets past the first
// screens; a random click or key can still end it anywhere (a widget not on screen, a button
// disabled by the e-stop) with an error naming the line.
const std::vector<std::string> kWorkflow = {"click Beacons##step",
                                            "click object:plate",
                                            "wait-idle 30",
                                            "click Calibrate##step",
                                            "click Collect points and fit",
                                            "wait-idle 300",
                                            "click Record##step",
                                            "click Start recording",
                                            "wait-idle 300",
                                            "click Start recording",
                                            "wait-idle 300",
                                            "click Play data##step",
                                            "click Record 30 play samples",
                                            "wait-idle 120",
                                            "click Train##step",
                                            "click Train Baseline and RECON",
                                            "wait-idle 600",
                                            "click Rollouts##step",
                                            "click Run rollouts",
                                            "wait-idle 600",
                                            "click Scene >",
                                            "click Play",
                                            "click Report##step",
                                            "click Write the report",
                                            "wait-idle 120"};

/// A random line that is not a click: a key, typing, a wait, a screenshot or a comment.
std::string NoiseLine(std::mt19937& rng, int line) {
  const auto uniform = [&](int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi)(rng);
  };
  const auto any = [&](const std::vector<std::string>& from) {
    return from[static_cast<size_t>(uniform(0, static_cast<int>(from.size()) - 1))];
  };
  const int kind = uniform(0, 99);
  if (kind < 20) return "press " + any(kKeys);
  if (kind < 35) return "hold " + any(kKeys) + " " + std::to_string(uniform(1, 6) * 0.05);
  if (kind < 50) {
    std::string typed;
    for (int c = uniform(1, 12); c > 0; --c) typed += static_cast<char>(uniform(32, 126));
    return "type " + typed;
  }
  if (kind < 70) return "wait " + std::to_string(uniform(0, 10));
  if (kind < 78) return "wait-idle 300";
  if (kind < 84) return "sleep 0.2";
  if (kind < 95) {
    return "screenshot " + std::string(uniform(0, 1) == 1 ? "deeper/" : "") + "shot_" +
           std::to_string(line) + ".png";
  }
  return uniform(0, 1) == 1 ? "# a comment" : "";
}

/// A script of `lines` lines from `seed`: the workflow's clicks in order, with random lines and
/// random clicks between; with `bad`, one line is one the parser refuses.
FuzzScript DrawScript(uint32_t seed, int lines, bool bad) {
  std::mt19937 rng(seed);
  const auto uniform = [&](int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi)(rng);
  };
  const auto any = [&](const std::vector<std::string>& from) {
    return from[static_cast<size_t>(uniform(0, static_cast<int>(from.size()) - 1))];
  };
  FuzzScript script;
  const int bad_at = bad ? uniform(1, lines) : 0;
  size_t next_workflow = 0;
  for (int line = 1; line <= lines; ++line) {
    std::string text;
    const int kind = uniform(0, 99);
    if (line == bad_at) {
      text = any(kBadLines);
      script.first_bad_line = line;
    } else if (kind < 2) {
      text = "click " + any(kLabels);
    } else if (kind < 35 || next_workflow == kWorkflow.size()) {
      text = NoiseLine(rng, line);
    } else {
      text = kWorkflow[next_workflow++];
    }
    script.text += text + "\n";
  }
  return script;
}

/// Every file under `dir` whose path relative to it is not one of `allowed_prefixes`.
std::vector<std::string> FilesOutside(const fs::path& dir,
                                      const std::vector<std::string>& allowed_prefixes) {
  std::vector<std::string> outside;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_directory()) continue;
    const std::string relative = fs::relative(entry.path(), dir).string();
    bool allowed = false;
    for (const std::string& prefix : allowed_prefixes) {
      allowed = allowed || relative.rfind(prefix, 0) == 0;
    }
    if (!allowed) outside.push_back(relative);
  }
  return outside;
}

std::string SeedName(const ::testing::TestParamInfo<uint32_t>& seed) {
  return "seed" + std::to_string(seed.param);
}

void PlayAndCheck(uint32_t seed, bool bad) {
  const FuzzScript script = DrawScript(seed, 48, bad);
  SCOPED_TRACE("seed " + std::to_string(seed) + ", script:\n" + script.text);
  const fs::path root =
      fs::temp_directory_path() /
      ("recon-studio-fuzz-" + std::to_string(getpid()) + "-" + std::to_string(seed));
  fs::remove_all(root);
  fs::create_directories(root / "tmp");
  const fs::path script_path = root / "fuzz.script";
  std::ofstream(script_path) << script.text;

  // The studio runs from the test's folder, with its home, temporary folder and configuration
  // there too, so a file it wrote anywhere unexpected would show up under `root`.
  const testing::CommandResult r = testing::RunCommand(
      "cd " + root.string() + " && HOME=" + (root / "home").string() +
      " TMPDIR=" + (root / "tmp").string() + " XDG_CONFIG_HOME=" + (root / "config").string() +
      " MESA_SHADER_CACHE_DISABLE=true " + RECON_STUDIO +
      " --headless --fast --session session --train-steps 30 --rollout-tests 2 --script " +
      script_path.string() + " --screenshots screens");
  // Where the script ended, so a run shows how deep into the workflow its seed got.
  const size_t last_line = r.output.find_last_of('\n', r.output.size() - 2);
  std::printf("seed %u: exit %d: %s\n", seed, r.exit_code,
              r.output.substr(last_line == std::string::npos ? 0 : last_line + 1).c_str());
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << "exit " << r.exit_code << ":\n" << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
  if (r.exit_code == 2) {
    EXPECT_NE(r.output.find(script_path.string() + ":"), std::string::npos)
        << "the error does not name the script's line:\n"
        << r.output;
  }
  if (bad) {
    // Refused whole before its first line ran: no screenshot, the bad line named.
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(
        r.output.find(script_path.string() + ":" + std::to_string(script.first_bad_line) + ": "),
        std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(root / "screens") && !fs::is_empty(root / "screens"));
  }

  // The session opens, and every file in it is whole (no temporary left, nothing cut short).
  if (fs::exists(root / "session")) {
    try {
      const store::Session session =
          store::Session::Open((root / "session").string(), store::Session::Access::kReadOnly);
      for (const store::EpisodeEntry& e : session.demos()) EXPECT_EQ(e.problem, "") << e.name;
      for (const store::EpisodeEntry& e : session.play_chunks()) EXPECT_EQ(e.problem, "") << e.name;
    } catch (const UserError& e) {
      ADD_FAILURE() << "the session does not open: " << e.what();
    }
    for (const auto& [name, bytes] : testing::Snapshot(root / "session")) {
      EXPECT_EQ(name.find(".tmp."), std::string::npos) << name;
      EXPECT_EQ(testing::Incomplete(root / "session" / name), "") << name;
    }
  }
  for (const auto& [name, bytes] : testing::Snapshot(root / "screens")) {
    EXPECT_TRUE(testing::EndsWith(name, ".png")) << name;
    EXPECT_EQ(testing::Incomplete(root / "screens" / name), "") << name;
  }
  EXPECT_EQ(FilesOutside(
                root, {"session/", "screens/", "config/recon-studio/recent.json", "fuzz.script"}),
            std::vector<std::string>{});
  if (!::testing::Test::HasFailure()) fs::remove_all(root);
}

// Seeds 1-10: scripts whose every line parses. They walk the workflow with random keys, typing,
// waits, screenshots and clicks between; a click may find its widget missing or disabled (an
// error naming the line, exit 2).
class StudioScriptFuzzTest : public ::testing::TestWithParam<uint32_t> {};

TEST_P(StudioScriptFuzzTest, AnyScriptEndsCleanlyAndLeavesTheSessionWhole) {
  PlayAndCheck(GetParam(), false);
}

INSTANTIATE_TEST_SUITE_P(Seeds, StudioScriptFuzzTest, ::testing::Range(1u, 11u), SeedName);

// Seeds 101-103: one refused line somewhere; the whole script is refused before it starts.
class StudioBadScriptFuzzTest : public ::testing::TestWithParam<uint32_t> {};

TEST_P(StudioBadScriptFuzzTest, AScriptWithABadLineIsRefusedBeforeItsFirstLineRuns) {
  PlayAndCheck(GetParam(), true);
}

INSTANTIATE_TEST_SUITE_P(Seeds, StudioBadScriptFuzzTest, ::testing::Values(101u, 102u, 103u),
                         SeedName);

}  // namespace
}  // namespace recon
