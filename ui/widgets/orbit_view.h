#pragma once

#include <optional>

#include "ui/studio/studio_commands.h"
#include "ui/studio/studio_snapshot.h"
#include "ui/widgets/image_texture.h"

namespace recon::ui {

/// The teacher's 3-D view of the cell, `width` pixels wide: dragging it with the left button
/// turns the view around the table (sideways: around; up and down: higher or lower), the mouse
/// wheel steps closer or back. A crosshair marks the grip point. Returns where the teacher asked
/// the view to look from this frame, if they moved it.
std::optional<SetTeacherView> OrbitView(const char* id, const ImageTexture& texture, float width,
                                        const TeacherView& view);

/// The preset views under the 3-D view (either side, the front, above), wrapped to `width`:
/// the one clicked, if any.
std::optional<SetTeacherView> OrbitPresets(const TeacherView& view, float width);

}  // namespace recon::ui
