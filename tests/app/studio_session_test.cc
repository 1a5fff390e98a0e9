// A whole teaching session driven through the studio's GUI, headless: the real recon-studio
// binary plays assets/studio/full_session.script (mark the plate, calibrate, record 4
// demonstrations and play data, train both methods, roll out, write the report). The test then
// checks the session on disk, not only pixels.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "engine/calib/calibration.h"
#include "engine/store/rollout_replay.h"
#include "engine/store/session.h"
#include "tests/support/golden_image.h"
#include "tests/support/run_command.h"

namespace recon {
namespace {

namespace fs = std::filesystem;

/// Runs recon-studio with `args`, its list of recent sessions kept under `config` (never the
/// user's own ~/.config); returns exit code and output.
testing::CommandResult RunStudio(const std::string& args,
                                 const fs::path& config = fs::temp_directory_path() /
                                                          ("recon-studio-config-" +
                                                           std::to_string(getpid()))) {
  return testing::RunCommand("XDG_CONFIG_HOME=" + config.string() + " " +
                             std::string(RECON_STUDIO) + " " + args);
}

TEST(StudioSessionTest, AWholeSessionThroughTheGuiEndsInAReport) {
  const fs::path dir = fs::temp_directory_path() / ("recon-studio-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const std::string session = (dir / "session").string();
  const std::string screens = (dir / "screens").string();
  const auto [code, output] = RunStudio(
      "--headless --fast --session " + session + " --train-steps 200 --rollout-tests 3 --script " +
      RECON_SOURCE_DIR + "/assets/studio/full_session.script --screenshots " + screens);
  ASSERT_EQ(code, 0) << output;
  // Errors the studio showed on screen are printed as lines starting "studio: ".
  EXPECT_EQ(("\n" + output).find("\nstudio: "), std::string::npos) << "the studio showed errors:\n"
                                                                   << output;

  const store::Session s = store::Session::Open(session, store::Session::Access::kReadOnly);
  const store::SessionManifest& m = s.manifest();
  EXPECT_EQ(m.world, "tabletop");
  ASSERT_EQ(m.beacon_assignments.count("plate"), 1u);  // clicked in the camera view
  EXPECT_EQ(m.beacon_assignments.at("plate"), "plate");
  ASSERT_FALSE(m.calibration_file.empty());
  EXPECT_TRUE(calib::LoadCalibration((fs::path(session) / m.calibration_file).string()).passed);
  // Four keyboard takes by the scripted person, who sees only the screen.
  ASSERT_EQ(s.demos().size(), 4u);
  std::set<uint64_t> seeds;
  for (const store::EpisodeEntry& e : s.demos()) {
    EXPECT_TRUE(e.problem.empty()) << e.problem;
    EXPECT_TRUE(e.meta.succeeded) << e.name;  // each take put the toast on the plate
    EXPECT_EQ(e.meta.source, "keyboard-teleop") << e.name;
    seeds.insert(e.meta.seed);
  }
  EXPECT_EQ(seeds.size(), 4u) << "every demonstration is a new scene";
  EXPECT_EQ(s.PlaySamples(), 30);
  for (const char* method : {"baseline", "recon"}) {
    EXPECT_TRUE(fs::exists(fs::path(session) / "checkpoints" / (std::string(method) + ".ckpt")));
    EXPECT_TRUE(fs::exists(fs::path(session) / "training" / (std::string(method) + ".json")));
    EXPECT_TRUE(fs::exists(fs::path(session) / "rollouts" / (std::string(method) + ".json")));
  }
  EXPECT_TRUE(fs::exists(fs::path(session) / "report" / "report.html"));
  // The rollouts ran on --rollout-tests scenes, and both methods kept them for playback.
  for (const char* method : {"baseline", "recon"}) {
    const store::RolloutReplay replay = store::ReadRolloutReplay(
        (fs::path(session) / "rollouts" / (std::string(method) + ".replay.h5")).string());
    EXPECT_EQ(replay.scenarios.size(), 3u) << method;
  }
  // A screenshot of every step, each a full window with content.
  for (const char* name : {"01_cell", "02_beacons", "03_calibrate", "04_record",
                           "04_record_countdown", "04_record_keyboard", "05_play", "06_train",
                           "07_rollouts", "07_rollouts_end", "07_rollouts_playing", "08_report"}) {
    const std::string path = screens + "/" + name + ".png";
    ASSERT_TRUE(fs::exists(path)) << path;
    const RgbImage image = testing::ReadPng(path);
    EXPECT_EQ(image.width, 1280);
    EXPECT_EQ(image.height, 800);
    std::set<uint32_t> colours;
    for (size_t i = 0; i + 2 < image.rgb.size(); i += 3 * 97) {
      colours.insert((image.rgb[i] << 16) | (image.rgb[i + 1] << 8) | image.rgb[i + 2]);
    }
    EXPECT_GT(colours.size(), 20u) << path << " looks blank";
  }
  fs::remove_all(dir);
}

TEST(StudioSessionTest, BadArgumentsAndScriptsAreClearErrors) {
  const fs::path dir = fs::temp_directory_path() / ("recon-studio-bad-" + std::to_string(getpid()));
  fs::remove_all(dir);
  testing::CommandResult r = RunStudio("--headless --frames 1 --width 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--width"), std::string::npos) << r.output;
  r = RunStudio("--headless --frames 1 --world dynamic2d --session " + (dir / "s").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("teaches in the tabletop cell"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "s"));
  fs::create_directories(dir);
  {
    std::ofstream script(dir / "bad.script");
    script << "wait 1\nclick Recrod##step\n";
  }
  r = RunStudio("--headless --session " + (dir / "t").string() + " --script " +
                (dir / "bad.script").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bad.script:2: no widget labelled 'Recrod##step'"), std::string::npos)
      << r.output;
  fs::remove_all(dir);
}

// Session > Quit closes the studio: a script ends there, and the lines after it (here one that
// would fail) never run.
TEST(StudioSessionTest, QuitFromTheSessionMenuEndsTheScript) {
  const fs::path dir =
      fs::temp_directory_path() / ("recon-studio-quit-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "quit.script") << "wait 2\nclick Session\nclick Quit\nclick Recrod##step\n";
  const testing::CommandResult r = RunStudio("--headless --session " + (dir / "s").string() +
                                             " --script " + (dir / "quit.script").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("recon-studio: session"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

// Without --session the studio starts at the session picker, offering what was opened before.
TEST(StudioSessionTest, WithoutASessionItStartsAtThePickerWithTheRecentOnes) {
  const fs::path dir =
      fs::temp_directory_path() / ("recon-studio-pick-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const fs::path config = dir / "config";
  testing::CommandResult r =
      RunStudio("--headless --frames 2 --session " + (dir / "toast").string(), config);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunStudio("--headless --frames 3 --screenshot " + (dir / "picker.png").string(), config);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("recon-studio: no session open"), std::string::npos) << r.output;
  std::ifstream in(config / "recon-studio" / "recent.json");
  const std::string recent((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(recent.find((dir / "toast").string()), std::string::npos) << recent;
  const RgbImage picker = testing::ReadPng((dir / "picker.png").string());
  EXPECT_EQ(picker.width, 1280);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon
