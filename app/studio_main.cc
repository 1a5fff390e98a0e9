// recon-studio: the interactive teaching studio. Wiring only: the controller (app/studio) owns
// the session and the cell, the screens (ui/) draw its snapshots and send commands back.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <variant>

#include "app/cli/option_checks.h"
#include "app/cli/run_main.h"
#include "app/studio/studio_controller.h"
#include "app/studio/studio_options.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/malloc_tuning.h"
#include "engine/report/image_png.h"
#include "ui/platform/desktop_window.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"
#include "ui/widgets/widget_registry.h"

namespace {

using recon::studio::StudioFlags;

std::string ReadScript(const std::string& path) {
  std::optional<std::string> text = recon::ReadWholeFile(path);
  if (!text) throw recon::UserError("cannot read the script " + path);
  return *text;
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
    options.renderer = {flags.width, flags.height, 16.0f, flags.ui_scale};
    options.min_width = recon::ui::kMinWindowWidth;
    options.min_height = recon::ui::kMinWindowHeight;
    options.ui_scale_from_screen = !(flags.ui_scale > 0);
    options.min_ui_scale = static_cast<float>(recon::cli::kMinUiScale);
    options.max_ui_scale = static_cast<float>(recon::cli::kMaxUiScale);
    try {
      auto window = std::make_unique<recon::ui::DesktopWindow>(options);
      std::printf("recon-studio: window on display %s (%s), UI scale %.2g\n", display.c_str(),
                  window->description().c_str(), window->ui_scale());
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
  // A script plays the simulated cell on a clock its frames move: the same session on any
  // machine, however loaded. A real cell's devices keep their own time.
  if (!flags.script.empty() && flags.options.cell_profile.empty()) {
    flags.options.clock = std::make_shared<recon::SteppedClock>();
  }
  // The desktop window before the controller: its GL context is made before the controller's
  // threads make theirs and destroyed after them (Mesa's llvmpipe has crashed while threads made
  // and dropped contexts side by side, see devices/render/egl_context.cc).
  std::string why_headless;
  const std::unique_ptr<recon::ui::DesktopWindow> desktop = OpenDesktopWindow(flags, why_headless);
  recon::studio::StudioController controller(flags.options);
  // Windows before the textures, which live in the window's GL context.
  std::optional<recon::ui::HeadlessWindow> window;
  if (desktop == nullptr) {
    window.emplace(recon::ui::UiRenderer::Options{flags.width, flags.height, 16.0f,
                                                  flags.ui_scale > 0 ? flags.ui_scale : 1.0f});
  }
  std::fflush(stdout);
  recon::ui::StudioTextures textures;
  recon::ui::CommandQueue commands;
  recon::ui::StudioSnapshot snapshot;
  bool quit = false;  // Session > Quit: the window closes as with its close button
  // The close button pressed while something runs: the screens ask before anything is stopped.
  bool close_asked = false;
  const auto draw = [&] {
    snapshot = controller.Snapshot();
    if (close_asked && snapshot.busy_with.empty()) quit = true;  // it ended meanwhile: close
    snapshot.close_requested = close_asked && !quit;
    recon::ui::DrawStudio(snapshot, commands, textures);
    for (recon::ui::StudioCommand& command : commands.Drain()) {
      if (std::holds_alternative<recon::ui::Quit>(command)) {
        quit = true;
      } else if (const auto* answer = std::get_if<recon::ui::AnswerClose>(&command)) {
        // Stopping is the controller's closing: a training's note stays in the session.
        quit = answer->close;
        close_asked = false;
      } else {
        controller.Push(std::move(command));
      }
    }
  };
  if (desktop != nullptr) {
    desktop->SetCloseGuard([&] {
      if (controller.Snapshot().busy_with.empty()) return true;
      close_asked = true;
      return false;
    });
    const auto frame = [&] {
      // Widgets note where they were drawn (for scripted clicks): forget the last frame's.
      recon::ui::WidgetRegistry::ForThisThread().BeginFrame();
      draw();
    };
    while (!quit && (!flags.frames_given || desktop->frames() < flags.frames) &&
           desktop->Frame(frame)) {
    }
    if (!flags.screenshot.empty()) WriteScreenshot(desktop->Screenshot(), flags.screenshot);
  } else {
    recon::ui::UiDriver driver(*window, draw);
    driver.SetIdleCheck([&] { return controller.Idle(); });
    driver.SetSettledCheck([&] { return controller.Settled(); });
    driver.SetQuitCheck([&] { return quit; });
    driver.SetSnapshotSource([&] { return controller.Snapshot(); });
    if (flags.options.clock) {
      driver.SetClock(flags.options.clock,
                      [&](recon::SteppedClock::time_point t) { return controller.CaughtUp(t); });
    }
    if (!flags.screenshots.empty()) {
      fs::create_directories(flags.screenshots);
      driver.SetScreenshotDir(flags.screenshots);
    }
    if (!flags.script.empty()) {
      try {
        driver.RunScript(ReadScript(flags.script), flags.script);
      } catch (...) {
        // What the screen showed when the script stopped (a failed save, a device gone) is often
        // why it stopped: print it before the script's own error.
        for (const std::string& error : controller.Snapshot().errors) {
          std::fprintf(stderr, "studio: %s\n", error.c_str());
        }
        throw;
      }
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
  CLI::Option* frames = recon::studio::AddStudioOptions(app, flags);
  return recon::cli::RunMain(app, argc, argv, "recon-studio", [&] {
    flags.frames_given = frames->count() > 0;
    Run(flags);
  });
}
