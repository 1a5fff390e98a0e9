#include "app/studio/gamepad_source.h"

#include "engine/core/error.h"

namespace recon::studio {

GamepadSource::GamepadSource(std::vector<std::string> paths) : paths_(std::move(paths)) {}

GamepadSource::~GamepadSource() = default;

std::string GamepadSource::Places() const {
  if (paths_.empty()) return "SDL's game controllers, /dev/input/js*";
  std::string places;
  for (const std::string& p : paths_) places += (places.empty() ? "" : ", ") + p;
  return places;
}

bool GamepadSource::Scan() {
  sdl_.reset();
  pad_.reset();
  if (paths_.empty()) {
    try {
      std::string unmapped;
      sdl_ = teleop::SdlGamepad::OpenFirst(&unmapped);
      if (sdl_) return true;
      if (!unmapped.empty()) error_ = "SDL has no mapping for " + unmapped;
    } catch (const UserError& e) {
      error_ = e.what();  // the joystick API may still read a pad
    }
  }
  for (const std::string& path : paths_.empty() ? teleop::LinuxJoystick::Find() : paths_) {
    try {
      pad_ = std::make_unique<teleop::LinuxJoystick>(path);
      return true;
    } catch (const UserError& e) {
      error_ = e.what();
    }
  }
  return false;
}

bool GamepadSource::Poll(std::chrono::steady_clock::time_point now) {
  command_ = {};
  bool changed = false;
  if (!connected() && now >= next_scan_) {
    next_scan_ = now + std::chrono::seconds(2);
    if (Scan()) {
      before_ = {};
      error_.clear();
      changed = true;
    }
  }
  if (!connected()) return changed;
  teleop::StandardPad state;
  if (sdl_) {
    if (!sdl_->Poll()) {
      error_ = sdl_->last_error();
      return true;
    }
    state = sdl_->state();
  } else {
    if (!pad_->Poll()) {
      error_ = pad_->last_error();
      return true;
    }
    state = teleop::FromXpadNumbering(pad_->state());
  }
  command_ = teleop::MapGamepad(state, before_);
  before_ = state;
  return changed;
}

ui::DeviceView GamepadSource::View() const {
  if (!connected()) {
    return {"teleop", "gamepad", "none found (looked for " + Places() + ")", false, 0.0, error_};
  }
  const std::string where =
      sdl_ ? sdl_->name() + " (" + sdl_->where() + ")" : pad_->name() + " at " + pad_->path();
  return {"teleop",
          "gamepad",
          where + ": left stick moves the arm, right stick raises it, A grips, Start keeps",
          true,
          0.0,
          ""};
}

}  // namespace recon::studio
