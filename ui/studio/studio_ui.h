#pragma once

#include "ui/screens/screens.h"

namespace recon::ui {

/// Draws the whole studio window for one frame: the step list on the left, the current step's
/// screen on the right, a status line at the bottom. A pure function of `snapshot` apart from
/// the commands it pushes and the textures it refreshes; GL thread only.
void DrawStudio(const StudioSnapshot& snapshot, CommandQueue& commands, StudioTextures& textures);

}  // namespace recon::ui
