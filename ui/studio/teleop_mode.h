#pragma once

namespace recon::ui {

/// Who drives the arm in the next demonstration: the simulated cell's scripted teacher, or a
/// person with the keyboard or a gamepad.
enum class TeleopMode { kScripted, kKeyboard, kGamepad };

/// The mode as the Record screen names it ("Scripted", "Keyboard", "Gamepad"). Studio scripts
/// click these labels, so they stay as they are.
inline const char* TeleopModeLabel(TeleopMode mode) {
  switch (mode) {
    case TeleopMode::kScripted:
      return "Scripted";
    case TeleopMode::kKeyboard:
      return "Keyboard";
    case TeleopMode::kGamepad:
      return "Gamepad";
  }
  return "?";
}

}  // namespace recon::ui
