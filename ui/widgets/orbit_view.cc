#include "ui/widgets/orbit_view.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

// Degrees per dragged pixel (at UI scale 1), and the distance factor per wheel notch.
constexpr float kDegreesPerPixel = 0.4f;
constexpr float kZoomPerNotch = 0.9f;

}  // namespace

std::optional<SetTeacherView> OrbitView(const char* id, const ImageTexture& texture, float width,
                                        const TeacherView& view) {
  if (texture.id() == nullptr || texture.width() <= 0) {
    ImGui::TextDisabled("No 3-D view yet.");
    return std::nullopt;
  }
  const float scale = width / static_cast<float>(texture.width());
  const ImVec2 size(width, texture.height() * scale);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::Image(texture.id(), size);
  ImGui::SetCursorScreenPos(origin);
  const ImGuiID base_id = ImGui::GetID(id);  // the button's own id: where its drag's base is kept
  ImGui::InvisibleButton(id, size);
  WidgetRegistry::ForThisThread().AddLastItem(id);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 grip(origin.x + view.grip_pixel[0] * scale, origin.y + view.grip_pixel[1] * scale);
  const float arm = Px(7);
  draw->AddLine(ImVec2(grip.x - arm, grip.y), ImVec2(grip.x + arm, grip.y),
                IM_COL32(255, 255, 255, 220), 1.5f);
  draw->AddLine(ImVec2(grip.x, grip.y - arm), ImVec2(grip.x, grip.y + arm),
                IM_COL32(255, 255, 255, 220), 1.5f);
  // The jaw's closing axis through the spot: a close holds what lies on it between the fingers.
  const std::array<float, 4>& jaw = view.jaw_pixels;
  if (jaw[0] != jaw[2] || jaw[1] != jaw[3]) {
    draw->AddLine(ImVec2(origin.x + jaw[0] * scale, origin.y + jaw[1] * scale),
                  ImVec2(origin.x + jaw[2] * scale, origin.y + jaw[3] * scale),
                  IM_COL32(30, 215, 240, 235), Px(2.5f));
  }

  // A drag is measured from where it started, against the view as it was then: the snapshot
  // lags the commands by a frame or two, and adding each frame's motion to it would lose some.
  ImGuiStorage* storage = ImGui::GetStateStorage();
  if (ImGui::IsItemActivated()) {
    storage->SetFloat(base_id, view.azimuth_deg);
    storage->SetFloat(base_id + 1, view.elevation_deg);
  }
  SetTeacherView wanted{view.azimuth_deg, view.elevation_deg, view.distance_m};
  bool moved = false;
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) {
    const ImVec2 drag = ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f);
    // Dragging right turns the table to the right (the camera goes left around it); dragging
    // down looks from higher up.
    wanted.azimuth_deg =
        storage->GetFloat(base_id, view.azimuth_deg) - drag.x / Px(1) * kDegreesPerPixel;
    wanted.elevation_deg =
        storage->GetFloat(base_id + 1, view.elevation_deg) - drag.y / Px(1) * kDegreesPerPixel;
    moved = wanted.azimuth_deg != view.azimuth_deg || wanted.elevation_deg != view.elevation_deg;
  }
  const float wheel = ImGui::GetIO().MouseWheel;
  if (ImGui::IsItemHovered() && wheel != 0.0f) {
    wanted.distance_m = view.distance_m * std::pow(kZoomPerNotch, wheel);
    moved = true;
  }
  ImGui::SetCursorScreenPos(ImVec2(origin.x, origin.y + size.y + ImGui::GetStyle().ItemSpacing.y));
  ImGui::Dummy(ImVec2(0, 0));
  if (!moved) return std::nullopt;
  return wanted;
}

std::optional<SetTeacherView> OrbitPresets(const TeacherView& view, float width) {
  struct Preset {
    const char* label;
    float azimuth_deg, elevation_deg;
  };
  // From either side (the studio starts from the right) the gripper coming down onto the toast
  // is not hidden by the arm, as it is from behind the robot.
  static constexpr Preset kPresets[] = {{"Right side##view", 90.0f, -35.0f},
                                        {"Left side##view", -90.0f, -35.0f},
                                        {"Front##view", 180.0f, -40.0f},
                                        {"Above##view", 90.0f, -89.0f}};
  std::optional<SetTeacherView> chosen;
  const ImGuiStyle& style = ImGui::GetStyle();
  float row = 0;  // the width taken on this row so far
  for (const Preset& preset : kPresets) {
    // Wrapped to the view's width, so a narrow window does not push what stands beside it.
    const float button =
        ImGui::CalcTextSize(preset.label, nullptr, true).x + 2 * style.FramePadding.x;
    if (row > 0 && row + style.ItemSpacing.x + button <= width) {
      ImGui::SameLine();
      row += style.ItemSpacing.x + button;
    } else {
      row = button;
    }
    if (Button(preset.label)) {
      chosen = SetTeacherView{preset.azimuth_deg, preset.elevation_deg, view.distance_m};
    }
  }
  return chosen;
}

}  // namespace recon::ui
