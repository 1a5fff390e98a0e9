#include "ui/widgets/widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>

#include "ui/widgets/widget_registry.h"

namespace recon::ui {

namespace {

ImU32 StatusColour(Status status) {
  switch (status) {
    case Status::kOk:
      return IM_COL32(0, 158, 115, 255);  // Okabe-Ito green
    case Status::kWarning:
      return IM_COL32(230, 159, 0, 255);  // orange
    case Status::kError:
      return IM_COL32(213, 94, 0, 255);  // vermillion
    case Status::kBusy:
      return IM_COL32(0, 114, 178, 255);  // blue
    case Status::kOff:
      break;
  }
  return IM_COL32(150, 150, 150, 255);
}

}  // namespace

float Px(float px) { return px * ImGui::GetFontSize() / 16.0f; }

float GrowingViewWidth(float share, float min_width, float max_width) {
  const float room = ImGui::GetContentRegionAvail().x;
  const float tall = 0.6f * ImGui::GetWindowHeight() * 4.0f / 3.0f;
  return std::clamp(room * share, min_width, std::max(max_width, tall));
}

namespace {

/// Why the last item (`id`, disabled) cannot be used, as a tooltip once the pointer has been
/// moved onto it and rested a moment. Not for a pointer that stayed where it clicked: a button
/// turns disabled under it (Start recording while the take counts down), and a tooltip then
/// would cover what the click brought up.
void ShowWhyDisabled(ImGuiID id, const std::string& why_disabled) {
  constexpr float kDelay_s = 0.4f;
  ImGuiStorage* storage = ImGui::GetStateStorage();
  if (why_disabled.empty() || !ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    storage->SetFloat(id, -1.0f);
    return;
  }
  const ImVec2 moved = ImGui::GetIO().MouseDelta;
  const float now = static_cast<float>(ImGui::GetTime());
  float since = storage->GetFloat(id, -1.0f);
  if (since < 0) {
    if (moved.x == 0 && moved.y == 0) return;
    since = now;
    storage->SetFloat(id, since);
  }
  if (now - since >= kDelay_s) ImGui::SetTooltip("%s", why_disabled.c_str());
}

}  // namespace

bool Button(const char* label, bool enabled, const std::string& why_disabled, float width) {
  if (!enabled) ImGui::BeginDisabled();
  const ImGuiID id = ImGui::GetID(label);
  const bool clicked = ImGui::Button(label, ImVec2(width, 0));
  WidgetRegistry::ForThisThread().AddLastItem(label, enabled);
  if (!enabled) {
    ImGui::EndDisabled();
    ShowWhyDisabled(id, why_disabled);
  }
  return clicked && enabled;
}

bool Selectable(const char* label, bool selected, bool enabled) {
  const bool clicked = ImGui::Selectable(
      label, selected, enabled ? ImGuiSelectableFlags_None : ImGuiSelectableFlags_Disabled);
  WidgetRegistry::ForThisThread().AddLastItem(label, enabled);
  return clicked && enabled;
}

bool SelectableRow(const char* label, bool selected, bool enabled) {
  ImGuiSelectableFlags flags =
      ImGuiSelectableFlags_SpanAllColumns | ImGuiSelectableFlags_AllowItemOverlap;
  if (!enabled) flags |= ImGuiSelectableFlags_Disabled;
  // As high as the buttons it holds.
  const bool clicked =
      ImGui::Selectable(label, selected, flags, ImVec2(0, ImGui::GetFrameHeight()));
  // Registered without the spacing ImGui adds above and below, which overlaps the next row.
  const float gap = ImGui::GetStyle().ItemSpacing.y * 0.5f;
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  WidgetRegistry::ForThisThread().AddRegion(label,
                                            {min.x, min.y + gap, max.x, max.y - gap, enabled});
  return clicked && enabled;
}

bool BeginCombo(const char* label, const char* preview) {
  const bool open = ImGui::BeginCombo(label, preview);
  WidgetRegistry::ForThisThread().AddLastItem(label);
  return open;
}

bool BeginMenu(const char* label, bool enabled) {
  const bool open = ImGui::BeginMenu(label, enabled);
  WidgetRegistry::ForThisThread().AddLastItem(label, enabled);
  return open;
}

bool MenuItem(const char* label, bool enabled, const std::string& why_disabled) {
  const bool clicked = ImGui::MenuItem(label, nullptr, false, enabled);
  WidgetRegistry::ForThisThread().AddLastItem(label, enabled);
  if (!enabled && !why_disabled.empty() &&
      ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", why_disabled.c_str());
  }
  return clicked && enabled;
}

bool InputText(const char* label, char* buffer, size_t size, float width) {
  ImGui::SetNextItemWidth(width);
  const bool entered = ImGui::InputText(label, buffer, size, ImGuiInputTextFlags_EnterReturnsTrue);
  WidgetRegistry::ForThisThread().AddLastItem(label);
  return entered;
}

void StatusText(Status status, const std::string& text) {
  const float size = ImGui::GetTextLineHeight();
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImGui::GetWindowDrawList()->AddCircleFilled(ImVec2(at.x + size * 0.4f, at.y + size * 0.55f),
                                              size * 0.3f, StatusColour(status));
  ImGui::Dummy(ImVec2(size * 0.9f, size));
  ImGui::SameLine();
  ImGui::TextUnformatted(text.c_str());
}

std::string Format(const char* format, ...) {
  char text[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof(text), format, args);
  va_end(args);
  return text;
}

void HintText(const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

void ScreenHeader(const std::string& title, const std::string& purpose) {
  ImGui::SetWindowFontScale(1.35f);
  ImGui::TextUnformatted(title.c_str());
  ImGui::SetWindowFontScale(1.0f);
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", purpose.c_str());
  ImGui::PopStyleColor();
  ImGui::Separator();
}

}  // namespace recon::ui
