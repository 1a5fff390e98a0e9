#pragma once

struct ImGuiStyle;

namespace recon::ui {

/// The studio's look: a light theme with one accent colour, generous spacing for a lab screen,
/// no rounding surprises. Pinned in code so golden screenshots stay stable.
void ApplyStudioStyle(ImGuiStyle& style);

}  // namespace recon::ui
