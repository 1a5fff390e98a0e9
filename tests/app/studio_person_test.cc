// Whether a person can teach from the studio's screen: a scripted person (ui::KeyboardPerson)
// that sees only what the Record screen draws (the teacher's 3-D view, the height readout and
// its grasp band, the grip's state) gives keyboard demonstrations through the screen's keys, in
// the real studio (controller, simulated cell, headless window), on ten new scenes.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include "app/studio/studio_controller.h"
#include "tests/app/headless_studio.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;

// The steps before Record, as a teacher clicks them: mark the plate, calibrate, choose the
// keyboard.
void ReachRecordWithTheKeyboard(ui::UiDriver& driver) {
  driver.RunScript(R"(wait 3
click Beacons##step
click object:plate
wait-idle 60
click Calibrate##step
click Collect points and fit
wait-idle 300
click Record##step
click [ ] Keyboard##teleop)",
                   "setup");
}

// Ten keyboard takes in a new session of the wide layout, where every take is a new scene (the
// plate anywhere along either edge, the bowl anywhere else): each one must put the toast on the
// plate at its first try. Prints how long each take took.
TEST(StudioPersonTest, APersonWhoOnlySeesTheScreenTeachesTenNewScenesAtTheFirstTry) {
  const fs::path dir = fs::temp_directory_path() / ("recon-person-" + std::to_string(getpid()));
  fs::remove_all(dir);
  StudioOptions options;
  options.session_dir = (dir / "session").string();
  options.recent_sessions_file = (dir / "config" / "recent.json").string();
  options.layout = "wide";
  options.seed = 11;
  options.countdown_s = 1;
  options.real_time = false;  // the calibration runs fast; a person's takes are paced anyway
  HeadlessStudio studio(options);
  ui::UiDriver& driver = studio.driver();
  ReachRecordWithTheKeyboard(driver);

  constexpr int kTakes = 10;
  int first_try = 0;
  double total_s = 0;
  std::printf("take  samples  seconds  wall_s  grasp_attempts  done\n");
  for (int take = 0; take < kTakes; ++take) {
    driver.Click("Start recording");
    const auto started = std::chrono::steady_clock::now();
    const ui::KeyboardPerson person = driver.KeyboardTake(120);
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    driver.WaitIdle(30);
    const ui::StudioSnapshot s = studio.controller().Snapshot();
    ASSERT_EQ(static_cast<int>(s.episodes.size()), take + 1)
        << "take " << take << " was not kept; " << person.Describe()
        << (s.pending_take.empty() ? "" : "; pending: " + s.pending_take);
    const ui::EpisodeView& episode = s.episodes.back();
    std::printf("%4d  %7d  %7.1f  %6.1f  %14d  %s\n", take, episode.samples, episode.seconds,
                wall_s, person.grasp_attempts(), episode.succeeded ? "yes" : "no");
    EXPECT_TRUE(episode.succeeded) << "take " << take << ": " << person.Describe();
    if (episode.succeeded) ++first_try;
    total_s += episode.seconds;
  }
  std::printf(
      "%d of %d takes done at the first try; %.1f s a take on average (seed %d, wide "
      "layout)\n",
      first_try, kTakes, total_s / kTakes, 11);
  EXPECT_EQ(first_try, kTakes);
  fs::remove_all(dir);
}

// The realistic person (reaction times, pauses, a misjudged depth: ui::PersonPace::Realistic)
// teaches the paper's protocol through the same screens, as a newcomer does: takes in which the
// task is done, a take that ended undone discarded and given again. It gets there,
// slower than the ideal person, and the takes end where a person ends them (the toast on the
// plate, the gripper clear) without pressing Enter. Prints the tries and the teacher's time.
TEST(StudioPersonTest, ARealisticPersonGetsATakeDoneThroughTheScreens) {
  const fs::path dir = fs::temp_directory_path() / ("recon-realistic-" + std::to_string(getpid()));
  fs::remove_all(dir);
  constexpr uint64_t kSeed = 3;
  // One take done: a whole session of such takes is what scripts/person-sessions measures.
  constexpr int kDemonstrations = 1;
  constexpr int kMaxTries = 12;
  std::printf("realistic person, seed %llu, paper layout, session seed 1\n",
              static_cast<unsigned long long>(kSeed));
  StudioOptions options;
  options.session_dir = (dir / "session").string();
  options.recent_sessions_file = (dir / "config" / "recent.json").string();
  options.countdown_s = 1;
  options.real_time = false;
  HeadlessStudio studio(options);
  ui::UiDriver& driver = studio.driver();
  ReachRecordWithTheKeyboard(driver);
  const ui::UiDriver::PersonTakesResult r = driver.PersonTakes(kDemonstrations, kSeed, kMaxTries);
  std::printf("%d demonstrations in %d tries, %d grasp attempts; %.1f s kept, %.1f s recorded\n",
              r.kept, r.tries, r.grasp_attempts, r.kept_seconds, r.total_seconds);
  const ui::StudioSnapshot s = studio.controller().Snapshot();
  ASSERT_EQ(s.episodes.size(), static_cast<size_t>(kDemonstrations));
  for (const ui::EpisodeView& e : s.episodes) {
    EXPECT_TRUE(e.succeeded) << e.name;
    // Ended by the goal with the gripper clear, at the latest at the take's limit.
    EXPECT_LE(e.samples, s.recording_max_samples) << e.name;
  }
  EXPECT_GE(r.tries, kDemonstrations);
  EXPECT_GE(r.grasp_attempts, kDemonstrations) << "every kept take closed the gripper";
  EXPECT_GE(r.total_seconds, r.kept_seconds);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon::studio
