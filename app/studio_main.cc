// recon-studio: the interactive teaching studio. Wiring only: the controller (app/studio) owns
// the session and the cell, the screens (ui/) draw its snapshots and send commands back.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/cli/run_main.h"
#include "app/studio/studio_controller.h"
#include "engine/core/error.h"
#include "engine/core/malloc_tuning.h"
#include "engine/report/image_png.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"

namespace {

struct StudioFlags {
  recon::studio::StudioOptions options;
  bool headless = false;
  bool fast = false;
  std::string script;
  std::string screenshots;
  std::string screenshot;
  int frames = 60;
  int width = 1280;
  int height = 800;
};

std::string ReadScript(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw recon::UserError("cannot read the script " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void Run(StudioFlags flags) {
  namespace fs = std::filesystem;
  if (flags.options.session_dir.empty()) {
    throw recon::UserError("give the session folder: recon-studio --session DIR (created if new)");
  }
  const bool display = std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY");
  if (!flags.headless && display) {
    std::fprintf(stderr,
                 "recon-studio: a desktop window is not built yet; running headless (as "
                 "--headless)\n");
  }
  flags.options.real_time = !flags.fast;
  recon::studio::StudioController controller(flags.options);
  recon::ui::HeadlessWindow window({flags.width, flags.height, 16.0f});
  recon::ui::StudioTextures textures;
  recon::ui::CommandQueue commands;
  recon::ui::StudioSnapshot snapshot;
  recon::ui::UiDriver driver(window, [&] {
    snapshot = controller.Snapshot();
    recon::ui::DrawStudio(snapshot, commands, textures);
    for (recon::ui::StudioCommand& command : commands.Drain()) controller.Push(std::move(command));
  });
  driver.SetIdleCheck([&] { return controller.Idle(); });
  driver.SetSettledCheck([&] { return controller.Settled(); });
  if (!flags.screenshots.empty()) {
    fs::create_directories(flags.screenshots);
    driver.SetScreenshotDir(flags.screenshots);
  }
  if (!flags.script.empty()) {
    driver.RunScript(ReadScript(flags.script), flags.script);
  } else {
    driver.WaitFrames(flags.frames);
  }
  if (!flags.screenshot.empty()) {
    recon::report::WritePng(driver.Screenshot(), flags.screenshot);
    std::printf("wrote %s\n", flags.screenshot.c_str());
  }
  const recon::ui::StudioSnapshot last = controller.Snapshot();
  for (const std::string& error : last.errors) std::fprintf(stderr, "studio: %s\n", error.c_str());
  std::printf("recon-studio: session %s, %zu demonstrations, %d play samples%s\n",
              last.session_dir.c_str(), last.episodes.size(), last.play_samples,
              last.report_path.empty() ? "" : (", report " + last.report_path).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  recon::TuneMallocForTraining();
  CLI::App app{"recon-studio: teach a robot with human-placed beacons"};
  StudioFlags flags;
  app.add_option("--session", flags.options.session_dir, "session folder (created if new)");
  app.add_option("--world", flags.options.world, "task of a new session")->capture_default_str();
  app.add_option("--seed", flags.options.seed, "seed of a new session")->capture_default_str();
  app.add_flag("--headless", flags.headless, "render through EGL without a window");
  app.add_flag("--fast", flags.fast,
               "record demonstrations as fast as the simulation runs (default: 10 Hz, real time)");
  app.add_option("--train-steps", flags.options.train_steps, "training steps per method")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--rollout-tests", flags.options.rollout_tests, "scenes per rollout run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--script", flags.script,
                 "play a script of inputs (click <label>, type, press, wait N, wait-idle, "
                 "screenshot <file>)");
  app.add_option("--screenshots", flags.screenshots, "folder for the script's screenshots");
  app.add_option("--screenshot", flags.screenshot, "write the last frame here (PNG)");
  app.add_option("--frames", flags.frames, "frames to run without a script")->capture_default_str();
  app.add_option("--width", flags.width, "window width")->capture_default_str();
  app.add_option("--height", flags.height, "window height")->capture_default_str();
  return recon::cli::RunMain(app, argc, argv, "recon-studio", [&] { Run(flags); });
}
