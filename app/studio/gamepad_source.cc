#include "app/studio/gamepad_source.h"

#include "engine/core/error.h"

namespace recon::studio {

GamepadSource::GamepadSource(std::vector<std::string> paths) : paths_(std::move(paths)) {}

std::string GamepadSource::Places() const {
  if (paths_.empty()) return "/dev/input/js*";
  std::string places;
  for (const std::string& p : paths_) places += (places.empty() ? "" : ", ") + p;
  return places;
}

bool GamepadSource::Poll(std::chrono::steady_clock::time_point now) {
  command_ = {};
  bool changed = false;
  if (!connected() && now >= next_scan_) {
    next_scan_ = now + std::chrono::seconds(2);
    for (const std::string& path : paths_.empty() ? teleop::LinuxJoystick::Find() : paths_) {
      try {
        pad_ = std::make_unique<teleop::LinuxJoystick>(path);
        before_ = {};
        error_.clear();
        changed = true;
        break;
      } catch (const UserError& e) {
        error_ = e.what();
      }
    }
  }
  if (!connected()) return changed;
  if (!pad_->Poll()) {
    error_ = pad_->last_error();
    return true;
  }
  command_ = teleop::MapGamepad(pad_->state(), before_);
  before_ = pad_->state();
  return changed;
}

ui::DeviceView GamepadSource::View() const {
  if (!connected()) {
    return {"teleop", "gamepad", "none found (looked for " + Places() + ")", false, 0.0, error_};
  }
  return {"teleop",
          "gamepad",
          pad_->name() + " at " + pad_->path() +
              ": left stick moves the arm, right stick raises it, A grips, Start keeps",
          true,
          0.0,
          ""};
}

}  // namespace recon::studio
