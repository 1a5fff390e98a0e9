#pragma once

// The options of `recon-studio`, on a CLI::App: the program (studio_main.cc) runs them, and tests
// walk them (every numeric option must be range-checked, as `recon`'s are).

#include <CLI/CLI.hpp>
#include <string>

#include "app/studio/studio_controller.h"

namespace recon::studio {

/// What the command line of recon-studio sets.
struct StudioFlags {
  StudioOptions options;
  bool headless = false;
  bool fast = false;
  std::string script;
  std::string screenshots;
  std::string screenshot;
  int frames = 60;
  bool frames_given = false;  ///< --frames on the command line: a window closes after them too
  int width = 1280;
  /// --ui-scale: the font and every size (2 on a high-DPI screen); 0 when not given: the
  /// screen's content scale in a desktop window, 1 headless.
  float ui_scale = 0.0f;
  int height = 800;
};

/// The most frames `--frames` takes: a day at 60 frames a second.
constexpr long long kMaxFrames = 24LL * 3600 * 60;

/// Adds every option of recon-studio to `app`, bound to `flags` (which must outlive it). Returns
/// the --frames option, whose count says whether it was given.
CLI::Option* AddStudioOptions(CLI::App& app, StudioFlags& flags);

}  // namespace recon::studio
