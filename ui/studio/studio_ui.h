#pragma once

#include "ui/screens/screens.h"

namespace recon::ui {

/// The smallest window every screen is laid out for, at UI scale 1 (times the scale above it):
/// a desktop window cannot be made smaller, and one that is anyway (a headless --width, a window
/// manager that ignores the limit) says so on its status line while its panels scroll.
constexpr int kMinWindowWidth = 1024;
constexpr int kMinWindowHeight = 640;

/// Draws the whole studio window for one frame: the step list on the left, the current step's
/// screen on the right, a status line at the bottom. A pure function of `snapshot` apart from
/// the commands it pushes and the textures it refreshes; GL thread only.
void DrawStudio(const StudioSnapshot& snapshot, CommandQueue& commands, StudioTextures& textures);

}  // namespace recon::ui
