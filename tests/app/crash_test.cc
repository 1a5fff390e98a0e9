// Crash safety of recording: `recon record` is killed with SIGKILL at seeded random moments, many
// times, appending to the same session. After every kill the session must open, every episode
// committed before must still be there, and every committed episode must hold exactly the data
// its scenario seed produces (recorded again here, in-process, as the reference).

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/rng.h"
#include "engine/store/session.h"
#include "engine/teach/recorder.h"
#include "engine/worlds/world_factory.h"
#include "tests/app/spawn_recon.h"

namespace recon {
namespace {

namespace fs = std::filesystem;

using testing::HasEnded;
using testing::SpawnRecon;
using testing::TemporaryFiles;

struct KillStats {
  int kills = 0;
  int mid_commit = 0;     ///< a temporary episode or index file existed at the kill
  int episodes_seen = 0;  ///< committed demonstrations at the end
  int play_chunks_seen = 0;
};

/// Files under the session's episodes/ and play/ folders, committed or half-written: how far a
/// run has got.
int EpisodeFiles(const fs::path& dir) {
  int count = 0;
  for (const char* folder : {"episodes", "play"}) {
    std::error_code error;  // a folder not created yet, or a file renamed while listed
    for (fs::directory_iterator it(dir / folder, error), end; !error && it != end;
         it.increment(error)) {
      ++count;
    }
  }
  return count;
}

/// The files one uninterrupted `recon record` with `record_args` writes, recording into `scratch`
/// instead of the session the args name. Kills are placed at a drawn number of these, not at a
/// time: a window timed from one run missed the later commits when other tests shared the CPU.
int FilesOfOneRun(std::vector<std::string> record_args, const fs::path& scratch) {
  for (size_t i = 0; i + 1 < record_args.size(); ++i) {
    if (record_args[i] == "--session") record_args[i + 1] = scratch.string();
  }
  fs::remove_all(scratch);
  const pid_t pid = SpawnRecon(record_args);
  int status = 0;
  waitpid(pid, &status, 0);
  const int files = EpisodeFiles(scratch);
  fs::remove_all(scratch);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the reference run failed";
  EXPECT_GT(files, 0) << "the reference run wrote no episode";
  return files;
}

/// Kills `recon record` `kills` times, each when the run has written a drawn number of files in
/// [0, files_per_run + 1] (0: in start-up; past the run's end: a completed run), and checks the
/// session after each kill against `expected_demo` / `expected_play` (the reference for a demo
/// or play number and size). The file that takes the count to its target is often still being
/// written, so many kills land in a commit in progress.
/// (void so that gtest's ASSERTs can stop it; the statistics come back through `stats`.)
template <typename ExpectedDemo, typename ExpectedPlay>
void KillRepeatedly(const fs::path& dir, const std::vector<std::string>& record_args, int kills,
                    int files_per_run, uint64_t seed, const ExpectedDemo& expected_demo,
                    const ExpectedPlay& expected_play, KillStats& stats, int min_mid_commit = 0) {
  Rng rng(seed);
  std::set<std::string> committed;  // names seen after earlier kills: they must survive
  // Episodes whose data was compared with the reference. Recording never rewrites a committed
  // file, so each is compared when it first appears and once more after the last kill.
  std::set<std::string> verified;
  // Past `kills`, keep killing (up to three times as often) until `min_mid_commit` of them have
  // hit a commit in progress.
  for (int k = 0; k < kills || (stats.mid_commit < min_mid_commit && k < 3 * kills); ++k) {
    const int before = EpisodeFiles(dir);
    const int target = static_cast<int>(rng.Uniform(0.0, files_per_run + 2.0));
    const pid_t pid = SpawnRecon(record_args);
    while (EpisodeFiles(dir) - before < target && !HasEnded(pid)) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    const std::string at = "kill " + std::to_string(k) + " (at file " + std::to_string(target) +
                           " of " + std::to_string(files_per_run) + ")";
    ++stats.kills;
    stats.mid_commit += TemporaryFiles(dir) > 0;
    if (!store::Session::Exists(dir.string())) {
      EXPECT_TRUE(committed.empty()) << at << ": the session's manifest disappeared";
      continue;  // killed before the session was created
    }
    const store::Session session = store::Session::Open(dir.string());
    std::set<std::string> now;
    for (const auto* list : {&session.demos(), &session.play_chunks()}) {
      for (const store::EpisodeEntry& e : *list) {
        now.insert(e.name);
        ASSERT_TRUE(e.problem.empty()) << at << " left a damaged episode: " << e.problem;
      }
    }
    for (const std::string& name : committed) {
      EXPECT_TRUE(now.count(name)) << at << " lost " << name;
    }
    committed = now;
    for (const store::EpisodeEntry& e : session.demos()) {
      if (!verified.insert(e.name).second && k + 1 < kills) continue;
      const store::DemoRecord got = session.ReadDemo(e.name);
      const Episode& want = expected_demo(e.number);
      ASSERT_EQ(got.episode.samples.size(), want.samples.size()) << e.name;
      for (size_t t = 0; t < want.samples.size(); ++t) {
        ASSERT_EQ(got.episode.samples[t].x, want.samples[t].x) << e.name << " sample " << t;
        ASSERT_EQ(got.episode.samples[t].y, want.samples[t].y) << e.name << " sample " << t;
        ASSERT_EQ(got.episode.samples[t].b, want.samples[t].b) << e.name << " sample " << t;
        ASSERT_EQ(got.episode.samples[t].u, want.samples[t].u) << e.name << " sample " << t;
      }
    }
    for (const store::EpisodeEntry& e : session.play_chunks()) {
      if (!verified.insert(e.name).second && k + 1 < kills) continue;
      const store::PlayRecord got = session.ReadPlay(e.name);
      const std::vector<PlaySample> want = expected_play(e.number, e.meta.num_samples);
      ASSERT_EQ(got.samples.size(), want.size()) << e.name;
      for (size_t t = 0; t < want.size(); ++t) {
        ASSERT_EQ(got.samples[t].y, want[t].y) << e.name << " sample " << t;
        ASSERT_EQ(got.samples[t].b, want[t].b) << e.name << " sample " << t;
      }
    }
    stats.episodes_seen = static_cast<int>(session.demos().size());
    stats.play_chunks_seen = static_cast<int>(session.play_chunks().size());
    // What the next run appends must continue the numbering without gaps from lost names.
    EXPECT_EQ(session.NextDemoNumber(), static_cast<int>(session.demos().size()));
  }
}

/// The reference recording of demonstration / play chunk `number` of a session seeded `seed`.
/// Recorded once per number and kept: the session is checked after every kill.
struct Reference {
  worlds::World& world;
  uint64_t seed;
  std::map<int, Episode> demos = {};
  const Episode& Demo(int number) {
    auto it = demos.find(number);
    if (it != demos.end()) return it->second;
    teach::DemoRecorder recorder(world, teach::ScriptedTeacher, "reference");
    recorder.Start(store::Session::ScenarioSeed(seed, number, false));
    while (recorder.Tick()) {
    }
    return demos[number] = recorder.Take().episode;
  }
  std::vector<PlaySample> Play(int number, int64_t size) const {
    return teach::RecordSessionPlayChunk(world, seed, number, static_cast<int>(size)).samples;
  }
};

TEST(CrashSafetyTest, KillNineWhileRecordingLosesAtMostTheEpisodeInProgress) {
  const fs::path dir = fs::temp_directory_path() / ("recon-crash-2d-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const std::unique_ptr<worlds::World> world = worlds::MakeWorld("dynamic2d", "exact", 0.0, false);
  Reference reference{*world, 5};
  // A run of 100 demonstrations and 60 play samples (120 files); kills land anywhere in it,
  // start-up included, and some after it ended (a completed run).
  const std::vector<std::string> args = {"record",    "--session", dir.string(), "--world",
                                         "dynamic2d", "--demos",   "100",        "--play",
                                         "60",        "--seed",    "5"};
  const int files = FilesOfOneRun(args, dir.string() + "-reference");
  KillStats stats;
  KillRepeatedly(
      dir, args, /*kills=*/30, files, /*seed=*/0xC4A5,
      [&](int n) -> const Episode& { return reference.Demo(n); },
      [&](int n, int64_t size) { return reference.Play(n, size); }, stats,
      /*min_mid_commit=*/3);
  std::printf(
      "dynamic2d: %d kills, %d in the middle of a commit; %d demonstrations and %d play "
      "chunks committed and intact (a whole run writes %d files; kill points seeded 0xC4A5)\n",
      stats.kills, stats.mid_commit, stats.episodes_seen, stats.play_chunks_seen, files);
  EXPECT_GT(stats.episodes_seen, 0);
  EXPECT_GT(stats.play_chunks_seen, 0);
  // The test is only worth something if kills hit commits in progress.
  EXPECT_GE(stats.mid_commit, 3);
  fs::remove_all(dir);
}

TEST(CrashSafetyTest, KillNineWhileRecordingCameraEpisodes) {
  const fs::path dir = fs::temp_directory_path() / ("recon-crash-tt-" + std::to_string(getpid()));
  fs::remove_all(dir);
  worlds::CellResources cell;
  cell.renderer_factory = render::MujocoRendererFactory();
  cell.image_size = 32;
  cell.layout = "wide";
  const std::unique_ptr<worlds::World> world =
      worlds::MakeWorld("tabletop", "plate", 0.0, false, cell);
  Reference reference{*world, 3};
  const std::vector<std::string> args = {"record", "--session", dir.string(), "--world", "tabletop",
                                         "--image-size", "32", "--demos", "20", "--play", "20",
                                         "--seed", "3", "--no-calibration",
                                         // The reference below records one scenario per seed
                                         // with exact beacons and no injected noise.
                                         "--layout", "wide", "--noise", "0", "--demo-noise", "0"};
  const int files = FilesOfOneRun(args, dir.string() + "-reference");
  KillStats stats;
  KillRepeatedly(
      dir, args, /*kills=*/5, files, /*seed=*/0x7AB1E,
      [&](int n) -> const Episode& { return reference.Demo(n); },
      [&](int n, int64_t size) { return reference.Play(n, size); }, stats);
  std::printf(
      "tabletop: %d kills, %d in the middle of a commit; %d demonstrations and %d play "
      "chunks committed and intact (a whole run writes %d files; kill points seeded 0x7AB1E)\n",
      stats.kills, stats.mid_commit, stats.episodes_seen, stats.play_chunks_seen, files);
  EXPECT_GT(stats.episodes_seen, 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon
