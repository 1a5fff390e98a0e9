#pragma once

#include <vector>

namespace recon::ui {

/// The e-stop's key, F12: one that nothing else in the studio uses, that no text field types
/// and no menu or popup closes with (Escape did both). ImGui 1.86 does not name F keys, so it
/// has an io.KeysDown slot of its own, above the letters' ASCII slots (see keys_down below).
inline constexpr int kEmergencyStopKey = 300;

/// Everything ImGui hears from the outside world in one frame. A window backend fills it from
/// GLFW events; the headless test driver fills it from a script. Fixed time steps and pinned
/// positions make frames reproducible, which the golden screenshots need.
struct FrameInput {
  static constexpr float kNoMouse = -1.0e30f;  ///< the pointer is outside the window
  float mouse_x = kNoMouse;
  float mouse_y = kNoMouse;
  bool mouse_down[3] = {false, false, false};  ///< left, right, middle
  float wheel = 0;
  std::vector<unsigned> characters;  ///< typed text (Unicode code points)
  std::vector<int> keys_pressed;     ///< ImGuiKey values pressed this frame (released next frame)
  std::vector<int> keys_down;        ///< ImGuiKey values held down this frame
  // ImGui 1.86 names only the letters A, C, V, X, Y and Z (for text shortcuts). A window also puts
  // every letter in both lists as its upper-case ASCII code ('W' = 87), an io.KeysDown slot that
  // no ImGuiKey uses, so a teleop can ask ImGui::IsKeyDown('W').
  bool ctrl = false, shift = false, alt = false;
  double delta_s = 1.0 / 60.0;
};

}  // namespace recon::ui
