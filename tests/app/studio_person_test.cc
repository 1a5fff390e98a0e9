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
  // The steps before Record, as a teacher clicks them.
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

}  // namespace
}  // namespace recon::studio
