#pragma once

#include <string>

#include "engine/core/image.h"

namespace recon::ui {

// The studio's widgets: ImGui's, registered by label for the test driver (widget_registry.h),
// and disabled ones say why on hover. Screens use these instead of raw ImGui buttons.

/// A button; when !enabled it is drawn greyed out, does nothing, and shows `why_disabled` on
/// hover. Returns true when clicked.
bool Button(const char* label, bool enabled = true, const std::string& why_disabled = "");
/// A selectable row (a list entry, a step in the sidebar).
bool Selectable(const char* label, bool selected, bool enabled = true);
/// A small coloured status dot followed by text (green ok, amber warning, red error, grey off).
enum class Status { kOk, kWarning, kError, kOff, kBusy };
void StatusText(Status status, const std::string& text);
/// printf-style formatting into a std::string, for labels built from numbers.
std::string Format(const char* format, ...) __attribute__((format(printf, 1, 2)));
/// A heading with the step's purpose under it.
void ScreenHeader(const std::string& title, const std::string& purpose);

}  // namespace recon::ui
