// Crash safety of what a session derives from its episodes: `recon train`, `recon eval`,
// `recon report` and `recon session export` are killed with SIGKILL at seeded moments (and an
// experiment once runs have finished: AKilledExperimentKeepsEveryRunItFinished). After
// every kill the session's episodes and manifest are byte for byte as before, and every derived
// file is the old one or a complete new one: a checkpoint is bitwise the old or the one an
// uninterrupted run writes (training is deterministic per seed), a result is parsable JSON, the
// report ends its HTML, the export imports. The next complete run leaves no temporary behind.

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/rng.h"
#include "engine/store/robomimic_io.h"
#include "engine/store/session.h"
#include "tests/app/spawn_recon.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::SpawnRecon;
using testing::TemporaryFiles;

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `recon` to the end; its exit code.
int RunToEnd(const std::vector<std::string>& args) {
  int status = 0;
  waitpid(SpawnRecon(args), &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The bytes of what a session is made of (manifest and episodes), by relative path.
std::map<std::string, std::string> Episodes(const fs::path& session) {
  std::map<std::string, std::string> files{{"session.json", Bytes(session / "session.json")}};
  for (const char* folder : {"episodes", "play"}) {
    for (const auto& entry : fs::directory_iterator(session / folder)) {
      files[fs::relative(entry.path(), session).string()] = Bytes(entry.path());
    }
  }
  return files;
}

/// Every derived file of the session is whole: checks one kill's aftermath.
void ExpectDerivedFilesWhole(const fs::path& session, const fs::path& export_file,
                             const std::map<std::string, std::string>& old_checkpoints,
                             const std::map<std::string, std::string>& new_checkpoints,
                             const std::string& where) {
  for (const auto& [name, old_bytes] : old_checkpoints) {
    const std::string now = Bytes(session / "checkpoints" / name);
    EXPECT_TRUE(now == old_bytes || now == new_checkpoints.at(name))
        << where << ": checkpoints/" << name << " is neither the old nor the new one ("
        << now.size() << " bytes)";
  }
  for (const char* folder : {"training", "rollouts"}) {
    for (const auto& entry : fs::directory_iterator(session / folder)) {
      if (entry.path().extension() != ".json") continue;
      const json record = json::parse(Bytes(entry.path()), nullptr, /*allow_exceptions=*/false);
      EXPECT_TRUE(record.is_object() && record.contains("method"))
          << where << ": " << entry.path() << " is not a whole result";
    }
  }
  const std::string html = Bytes(session / "report" / "report.html");
  EXPECT_NE(html.rfind("</html>"), std::string::npos) << where << ": report.html is cut";
  const fs::path copy = export_file.string() + "-imported";
  fs::remove_all(copy);
  EXPECT_NO_THROW(store::ImportRobomimic(export_file.string(), copy.string()))
      << where << ": the export no longer imports";
  fs::remove_all(copy);
}

TEST(CrashSafetyTest, KillNineDuringTrainEvalReportOrExportLeavesEveryFileOldOrWhole) {
  const fs::path root =
      fs::temp_directory_path() / ("recon-crash-results-" + std::to_string(getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  const fs::path session = root / "s";
  const fs::path exported = root / "s.hdf5";
  const std::string s = session.string();
  ASSERT_EQ(RunToEnd({"record", "--session", s, "--world", "dynamic2d", "--demos", "4", "--play",
                      "4", "--seed", "3"}),
            0);
  // What the commands below replace: a short training's models, their rollouts, a report, an
  // export.
  const std::vector<std::string> train = {
      "train", "--session", s, "--methods", "baseline,recon", "--steps", "3000", "--seed", "9"};
  ASSERT_EQ(RunToEnd({"train", "--session", s, "--methods", "baseline,recon", "--steps", "300",
                      "--seed", "9"}),
            0);
  ASSERT_EQ(RunToEnd({"eval", "--session", s, "--tests", "5"}), 0);
  ASSERT_EQ(RunToEnd({"report", s}), 0);
  ASSERT_EQ(RunToEnd({"session", "export", s, "--out", exported.string()}), 0);
  std::map<std::string, std::string> old_checkpoints, new_checkpoints;
  for (const char* name : {"baseline.ckpt", "recon.ckpt"}) {
    old_checkpoints[name] = Bytes(session / "checkpoints" / name);
  }
  // The checkpoints an uninterrupted `train` writes, from a copy of the session.
  const fs::path twin = root / "twin";
  fs::copy(session, twin, fs::copy_options::recursive);
  std::vector<std::string> twin_train = train;
  twin_train[2] = twin.string();
  ASSERT_EQ(RunToEnd(twin_train), 0);
  for (const char* name : {"baseline.ckpt", "recon.ckpt"}) {
    new_checkpoints[name] = Bytes(twin / "checkpoints" / name);
    ASSERT_NE(new_checkpoints[name], old_checkpoints[name]);
  }
  const std::map<std::string, std::string> episodes = Episodes(session);

  const std::vector<std::vector<std::string>> commands = {
      train,
      {"eval", "--session", s, "--tests", "20"},
      {"report", s},
      {"session", "export", s, "--out", exported.string(), "--force"}};
  Rng rng(0xD1E5);
  int kills = 0;
  for (const std::vector<std::string>& command : commands) {
    // Kills are placed in fractions of one whole run on a copy, so they land inside the run
    // however loaded the machine is.
    std::vector<std::string> timed = command;
    for (std::string& arg : timed) {
      if (arg == s) arg = twin.string();
      if (arg == exported.string()) arg = (root / "twin.hdf5").string();
    }
    const auto start = std::chrono::steady_clock::now();
    ASSERT_EQ(RunToEnd(timed), 0) << command[0];
    const double run_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (int k = 0; k < 6; ++k) {
      const double delay_s = rng.Uniform(0.1, 1.0) * run_s;
      const pid_t pid = SpawnRecon(command);
      std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
      kill(pid, SIGKILL);
      int status = 0;
      waitpid(pid, &status, 0);
      ++kills;
      const std::string where = command[0] + " killed after " + std::to_string(delay_s) + " s of " +
                                std::to_string(run_s) + " s";
      EXPECT_EQ(Episodes(session), episodes) << where << ": the session's episodes changed";
      EXPECT_NO_THROW(store::Session::Open(s, store::Session::Access::kReadOnly)) << where;
      ExpectDerivedFilesWhole(session, exported, old_checkpoints, new_checkpoints, where);
    }
    // A complete run removes what the killed ones left.
    ASSERT_EQ(RunToEnd(command), 0) << command[0];
  }
  EXPECT_EQ(TemporaryFiles(session), 0);
  EXPECT_EQ(TemporaryFiles(root), 0);
  std::printf("%d kills across train, eval, report and export (delays seeded 0xD1E5)\n", kills);
  fs::remove_all(root);
}

/// Lines of a text file (none if it does not exist).
std::vector<std::string> Lines(const fs::path& path) {
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// An experiment killed after an hour must not take the runs it finished with it: each finished
// run is in runs_so_far.csv (written whole after every run) until results.csv replaces it.
// Killed as soon as the first run's row is there, and once more when the second's is: the rows
// kept are whole, seeded, and the same as the complete experiment's.
TEST(CrashSafetyTest, AKilledExperimentKeepsEveryRunItFinished) {
  const fs::path root = fs::temp_directory_path() / ("recon-crash-exp-" + std::to_string(getpid()));
  fs::remove_all(root);
  const auto args = [&](const std::string& out) {
    // Runs long enough (about a second each) that a kill seen to follow a row's write lands
    // before the next run ends.
    return std::vector<std::string>{
        "experiment",       "static2d", "--demos",      "2",
        "--runs",           "4",        "--steps",      "600",
        "--baseline-steps", "600",      "--tests",      "2",
        "--jobs",           "1",        "--conditions", "baseline",
        "--seed",           "4",        "--out",        (root / out).string()};
  };
  ASSERT_EQ(RunToEnd(args("complete")), 0);
  const std::vector<std::string> complete = Lines(root / "complete" / "results.csv");
  ASSERT_EQ(complete.size(), 5u) << "a header and 4 runs";
  EXPECT_FALSE(fs::exists(root / "complete" / "runs_so_far.csv"))
      << "the runs so far outlived the complete results";
  for (const size_t rows : {1u, 2u}) {
    SCOPED_TRACE("killed once " + std::to_string(rows) + " run(s) had finished");
    const fs::path out = root / ("killed_" + std::to_string(rows));
    const fs::path partial = out / "runs_so_far.csv";
    const pid_t pid = SpawnRecon(args(out.filename().string()));
    while (Lines(partial).size() < rows + 1 && !testing::HasEnded(pid)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    const std::vector<std::string> kept = Lines(partial);
    ASSERT_GE(kept.size(), rows + 1);
    EXPECT_FALSE(fs::exists(out / "summary.json"));
    for (size_t i = 0; i < kept.size(); ++i) {
      // Seeds, metric, losses: identical (no wall-clock time in a row).
      EXPECT_EQ(kept[i], complete[i]) << "row " << i;
    }
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace recon
