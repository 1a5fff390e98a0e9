#include "ui/platform/studio_style.h"

#include <imgui.h>

namespace recon::ui {

void ApplyStudioStyle(ImGuiStyle& style) {
  ImGui::StyleColorsLight(&style);
  style.WindowRounding = 0.0f;
  style.FrameRounding = 4.0f;
  style.GrabRounding = 4.0f;
  style.ChildRounding = 4.0f;
  style.WindowPadding = ImVec2(14, 12);
  style.FramePadding = ImVec2(10, 6);
  style.ItemSpacing = ImVec2(10, 8);
  style.ScrollbarSize = 14.0f;
  style.WindowBorderSize = 0.0f;
  style.AntiAliasedLines = true;
  style.AntiAliasedFill = true;
  ImVec4* c = style.Colors;
  const ImVec4 accent(0.0f, 0.447f, 0.698f, 1.0f);  // the report's blue (Okabe-Ito)
  c[ImGuiCol_WindowBg] = ImVec4(0.975f, 0.977f, 0.98f, 1.0f);
  c[ImGuiCol_ChildBg] = ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
  c[ImGuiCol_Text] = ImVec4(0.11f, 0.12f, 0.14f, 1.0f);
  c[ImGuiCol_TextDisabled] = ImVec4(0.45f, 0.47f, 0.50f, 1.0f);
  // Buttons are tinted, not filled, so their dark labels stay readable.
  c[ImGuiCol_Button] = ImVec4(accent.x, accent.y, accent.z, 0.18f);
  c[ImGuiCol_ButtonHovered] = ImVec4(accent.x, accent.y, accent.z, 0.32f);
  c[ImGuiCol_ButtonActive] = ImVec4(accent.x, accent.y, accent.z, 0.46f);
  c[ImGuiCol_Header] = ImVec4(accent.x, accent.y, accent.z, 0.16f);
  c[ImGuiCol_HeaderHovered] = ImVec4(accent.x, accent.y, accent.z, 0.28f);
  c[ImGuiCol_HeaderActive] = ImVec4(accent.x, accent.y, accent.z, 0.40f);
  c[ImGuiCol_PlotLines] = accent;
  c[ImGuiCol_PlotHistogram] = accent;
  c[ImGuiCol_CheckMark] = accent;
  c[ImGuiCol_SliderGrab] = accent;
}

}  // namespace recon::ui
