#pragma once

#include <memory>
#include <optional>

#include "app/studio/studio_controller.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"
#include "ui/testing/ui_driver.h"

namespace recon::studio {

/// The studio as recon-studio --headless --script runs it, in this process: the simulated cell
/// on a SteppedClock that the driver's frames move (the same on any machine); a real cell (the
/// digital twin's devices keep their own time) on the steady clock.
class HeadlessStudio {
 public:
  explicit HeadlessStudio(const StudioOptions& options) : controller_(OnAClock(options)) {
    window_.emplace(ui::UiRenderer::Options{1280, 800, 16.0f, 1.0f});
    driver_.emplace(*window_, [this] {
      snapshot_ = controller_.Snapshot();
      ui::DrawStudio(snapshot_, commands_, textures_);
      for (ui::StudioCommand& command : commands_.Drain()) controller_.Push(std::move(command));
    });
    driver_->SetSettledCheck([this] { return controller_.Settled(); });
    driver_->SetIdleCheck([this] { return controller_.Idle(); });
    driver_->SetSnapshotSource([this] { return controller_.Snapshot(); });
    if (clock_) {
      driver_->SetClock(clock_,
                        [this](SteppedClock::time_point t) { return controller_.CaughtUp(t); });
    }
  }

  StudioController& controller() { return controller_; }
  ui::UiDriver& driver() { return *driver_; }

 private:
  StudioOptions OnAClock(StudioOptions options) {
    if (options.cell_profile.empty() && !options.clock) {
      options.clock = std::make_shared<SteppedClock>();
    }
    clock_ = options.clock;
    return options;
  }

  std::shared_ptr<SteppedClock> clock_;  // before the controller, which OnAClock gives it to
  StudioController controller_;
  std::optional<ui::HeadlessWindow> window_;  // after the controller, as in recon-studio
  ui::StudioTextures textures_;
  ui::CommandQueue commands_;
  ui::StudioSnapshot snapshot_;
  std::optional<ui::UiDriver> driver_;
};

}  // namespace recon::studio
