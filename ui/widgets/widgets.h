#pragma once

#include <cstddef>
#include <string>

#include "engine/core/image.h"

namespace recon::ui {

// The studio's widgets: ImGui's, registered by label for the test driver (widget_registry.h),
// and disabled ones say why on hover. Screens use these instead of raw ImGui buttons.

/// A button; when !enabled it is drawn greyed out, does nothing, and shows `why_disabled` on
/// hover. Returns true when clicked.
/// `width`: 0 fits the label; a fixed width keeps what follows in place when the label changes.
bool Button(const char* label, bool enabled = true, const std::string& why_disabled = "",
            float width = 0);
/// A selectable row (a list entry, a step in the sidebar).
bool Selectable(const char* label, bool selected, bool enabled = true);
/// A table row that is one click target across all its columns, in its first column: buttons
/// drawn in its other columns stay clickable over it. Registered as a region (it holds them).
bool SelectableRow(const char* label, bool selected, bool enabled = true);
/// A menu of the menu bar (true while open: draw its items, then ImGui::EndMenu) and its items.
bool BeginMenu(const char* label, bool enabled = true);
/// A drop-down list showing `preview`; its items are Selectables. End it with ImGui::EndCombo.
bool BeginCombo(const char* label, const char* preview);
bool MenuItem(const char* label, bool enabled = true, const std::string& why_disabled = "");
/// A one-line text field `width` pixels wide over `buffer`; true when Enter was pressed in it.
/// Clicking it (or the driver's `click <label>`) focuses it for typing.
bool InputText(const char* label, char* buffer, size_t size, float width);
/// A small coloured status dot followed by text (green ok, amber warning, red error, grey off).
enum class Status { kOk, kWarning, kError, kOff, kBusy };
void StatusText(Status status, const std::string& text);
/// A size in the studio's 1x pixels (laid out for a 16 px font) at the UI's scale: the screens
/// give every fixed size through it, so --ui-scale 2 doubles them with the font.
float Px(float px);
/// The width of a live view (a 4:3 image) that grows with the window: `share` of the room left
/// on the line, at least `min_width`, and at most `max_width` or, in a taller window, as wide as
/// 60 % of the panel's height allows (so what is under it stays in view).
float GrowingViewWidth(float share, float min_width, float max_width);
/// printf-style formatting into a std::string, for labels built from numbers.
std::string Format(const char* format, ...) __attribute__((format(printf, 1, 2)));
/// Greyed text wrapped at the panel's edge (or the wrap position pushed): a note or a hint that
/// may be long.
void HintText(const std::string& text);
/// A heading with the step's purpose under it.
void ScreenHeader(const std::string& title, const std::string& purpose);

}  // namespace recon::ui
