// recon-studio: the interactive teaching studio. Wiring only: the controller (app/studio) owns
// the session and the cell, the screens (ui/) draw its snapshots and send commands back.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/cli/option_checks.h"
#include "app/cli/run_main.h"
#include "app/studio/studio_controller.h"
#include "engine/core/error.h"
#include "engine/core/malloc_tuning.h"
#include "engine/report/image_png.h"
#include "ui/platform/desktop_window.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"
#include "ui/widgets/widget_registry.h"

namespace {

struct StudioFlags {
  recon::studio::StudioOptions options;
  bool headless = false;
  bool fast = false;
  std::string script;
  std::string screenshots;
  std::string screenshot;
  int frames = 60;
  bool frames_given = false;  ///< --frames on the command line: a window closes after them too
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

/// The display a desktop window would open on, or empty when there is none.
std::string DisplayName() {
  for (const char* variable : {"DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(variable);
    if (value != nullptr && *value != '\0') return value;
  }
  return "";
}

/// The studio's desktop window, or null with the reason in `why_not` when it is not wanted
/// (--headless, --script) or cannot open (no display, no OpenGL).
std::unique_ptr<recon::ui::DesktopWindow> OpenDesktopWindow(const StudioFlags& flags,
                                                            std::string& why_not) {
  const std::string display = DisplayName();
  if (flags.headless) {
    why_not = "--headless";
  } else if (!flags.script.empty()) {
    why_not = "a --script plays into a headless window";
  } else if (display.empty()) {
    why_not = "no display (DISPLAY and WAYLAND_DISPLAY are unset)";
  } else {
    recon::ui::DesktopWindow::Options options;
    options.title = flags.options.session_dir.empty()
                        ? std::string("RECON Studio")
                        : "RECON Studio - " + flags.options.session_dir;
    options.renderer = {flags.width, flags.height, 16.0f};
    try {
      auto window = std::make_unique<recon::ui::DesktopWindow>(options);
      std::printf("recon-studio: window on display %s (%s)\n", display.c_str(),
                  window->description().c_str());
      return window;
    } catch (const recon::UserError& e) {
      why_not = e.what();
    }
  }
  std::printf("recon-studio: headless (EGL): %s\n", why_not.c_str());
  return nullptr;
}

void WriteScreenshot(const recon::RgbImage& image, const std::string& path) {
  if (image.width == 0) throw recon::UserError("no frame was drawn, so none is written to " + path);
  recon::report::WritePng(image, path);
  std::printf("wrote %s\n", path.c_str());
}

void Run(StudioFlags flags) {
  namespace fs = std::filesystem;
  flags.options.real_time = !flags.fast;
  // The desktop window before the controller: its GL context is made before the controller's
  // threads make theirs and destroyed after them (Mesa's llvmpipe has crashed while threads made
  // and dropped contexts side by side, see devices/render/egl_context.cc).
  std::string why_headless;
  const std::unique_ptr<recon::ui::DesktopWindow> desktop = OpenDesktopWindow(flags, why_headless);
  recon::studio::StudioController controller(flags.options);
  // Windows before the textures, which live in the window's GL context.
  std::optional<recon::ui::HeadlessWindow> window;
  if (desktop == nullptr) window.emplace(recon::ui::UiRenderer::Options{flags.width, flags.height});
  std::fflush(stdout);
  recon::ui::StudioTextures textures;
  recon::ui::CommandQueue commands;
  recon::ui::StudioSnapshot snapshot;
  const auto draw = [&] {
    snapshot = controller.Snapshot();
    recon::ui::DrawStudio(snapshot, commands, textures);
    for (recon::ui::StudioCommand& command : commands.Drain()) controller.Push(std::move(command));
  };
  if (desktop != nullptr) {
    const auto frame = [&] {
      // Widgets note where they were drawn (for scripted clicks): forget the last frame's.
      recon::ui::WidgetRegistry::ForThisThread().BeginFrame();
      draw();
    };
    while ((!flags.frames_given || desktop->frames() < flags.frames) && desktop->Frame(frame)) {
    }
    if (!flags.screenshot.empty()) WriteScreenshot(desktop->Screenshot(), flags.screenshot);
  } else {
    recon::ui::UiDriver driver(*window, draw);
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
    if (!flags.screenshot.empty()) WriteScreenshot(driver.Screenshot(), flags.screenshot);
  }
  const recon::ui::StudioSnapshot last = controller.Snapshot();
  for (const std::string& error : last.errors) std::fprintf(stderr, "studio: %s\n", error.c_str());
  if (!last.session_open) {
    std::printf("recon-studio: no session open\n");
    return;
  }
  std::printf("recon-studio: session %s, %zu demonstrations, %d play samples%s\n",
              last.session_dir.c_str(), last.episodes.size(), last.play_samples,
              last.report_path.empty() ? "" : (", report " + last.report_path).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  recon::TuneMallocForTraining();
  CLI::App app{"recon-studio: teach a robot with human-placed beacons"};
  StudioFlags flags;
  app.add_option("--session", flags.options.session_dir,
                 "session folder (created if new); without, the studio starts at the session "
                 "picker with the recent sessions");
  app.add_option("--world", flags.options.world, "task of a new session")->capture_default_str();
  app.add_option("--seed", flags.options.seed, "seed of a new session")
      ->check(recon::cli::SeedNumber())
      ->capture_default_str();
  app.add_option("--layout", flags.options.layout,
                 "scene layout of a new tabletop session: paper (the plate at one of two "
                 "places, 2 demonstrations per configuration) or wide")
      ->check(CLI::IsMember({"paper", "wide"}))
      ->capture_default_str();
  app.add_option("--noise", flags.options.beacon_noise_sigma,
                 "beacon noise sigma per axis of a new simulated session, metres (default: a "
                 "DWM1001's 0.07 on the tabletop)")
      ->check(recon::cli::NumberBetween(0, 0.5));
  app.add_option("--demo-noise", flags.options.demo_noise_sigma,
                 "noise injected into the executed joint velocities while demonstrating in a new "
                 "session (DART, rad/s; 0 = off; default: 0.05 on the tabletop)")
      ->check(recon::cli::NumberBetween(0, recon::cli::kMaxDemoNoise_rad_s));
  app.add_flag("--headless", flags.headless, "render through EGL without a window");
  app.add_option("--cell", flags.options.cell_profile,
                 "teach with the real devices of this cell profile (JSON: camera, beacons, UR "
                 "robot; docs/hardware.md) instead of the simulated cell")
      ->check(CLI::ExistingFile);
  app.add_option("--calibration", flags.options.calibration_file,
                 "attach this calibration (recon calibrate --out) to the session")
      ->check(CLI::ExistingFile);
  app.add_option("--dev", flags.options.dev_dir,
                 "device folder the Cell screen lists beacons, cameras and gamepads from")
      ->capture_default_str();
  app.add_option("--robot-host", flags.options.robot_hosts,
                 "a UR controller the Cell screen lists (host or host:port; repeatable)");
  app.add_flag("--fast", flags.fast,
               "record demonstrations as fast as the simulation runs (default: 10 Hz, real time)");
  app.add_option("--train-steps", flags.options.train_steps,
                 "training steps per method (default: the world's recipe: 15000 on the "
                 "tabletop)")
      ->check(recon::cli::WholeBetween(1, recon::cli::kMaxSteps));
  app.add_option("--rollout-tests", flags.options.rollout_tests, "scenes per rollout run")
      ->check(recon::cli::WholeBetween(1, recon::cli::kMaxTests))
      ->capture_default_str();
  app.add_option("--script", flags.script,
                 "play a script of inputs (click <label>, type, press, wait N, wait-idle, "
                 "screenshot <file>)");
  app.add_option("--screenshots", flags.screenshots, "folder for the script's screenshots");
  app.add_option("--screenshot", flags.screenshot, "write the last frame here (PNG)");
  CLI::Option* frames =
      app.add_option("--frames", flags.frames,
                     "frames to run without a script (a window: until closed, unless given)")
          ->capture_default_str();
  app.add_option("--width", flags.width, "window width")
      ->check(recon::cli::WholeBetween(640, 8192))
      ->capture_default_str();
  app.add_option("--height", flags.height, "window height")
      ->check(recon::cli::WholeBetween(480, 8192))
      ->capture_default_str();
  return recon::cli::RunMain(app, argc, argv, "recon-studio", [&] {
    flags.frames_given = frames->count() > 0;
    Run(flags);
  });
}
