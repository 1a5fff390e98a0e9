#pragma once

// A headless studio window drawing whatever snapshot a test sets, and where the screens' goldens
// live: shared by the screen tests.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"

namespace recon::ui {

constexpr int kWidth = 1280;
constexpr int kHeight = 800;

/// A headless studio window drawing whatever snapshot the test sets.
class StudioHarness {
 public:
  explicit StudioHarness(int width = kWidth, int height = kHeight, float ui_scale = 1.0f)
      : window_({width, height, 16.0f, ui_scale}),
        driver_(window_, [this] { DrawStudio(snapshot_, commands_, textures_); }) {}

  void Show(const StudioSnapshot& snapshot) {
    snapshot_ = snapshot;
    driver_.WaitFrames(3);  // tables and wrapped text settle over two frames
  }
  UiDriver& driver() { return driver_; }
  std::vector<StudioCommand> Commands() { return commands_.Drain(); }

 private:
  // Declared so that the textures go before the window whose GL context owns them.
  StudioSnapshot snapshot_;
  CommandQueue commands_;
  HeadlessWindow window_;
  StudioTextures textures_;
  UiDriver driver_;
};

inline std::string GoldenPath(const std::string& name) {
  return std::string(RECON_SOURCE_DIR) + "/assets/goldens/studio_" + name + ".png";
}

/// The last command of type `Command` among `commands`, if any.
template <typename Command>
std::optional<Command> Last(const std::vector<StudioCommand>& commands) {
  std::optional<Command> last;
  for (const StudioCommand& c : commands) {
    if (const auto* command = std::get_if<Command>(&c)) last = *command;
  }
  return last;
}

}  // namespace recon::ui
