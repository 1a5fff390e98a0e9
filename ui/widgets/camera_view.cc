#include "ui/widgets/camera_view.h"

#include <imgui.h>

#include <cmath>

#include "ui/widgets/widget_registry.h"

namespace recon::ui {

std::optional<std::string> CameraView(const char* id, const ImageTexture& texture, float width,
                                      const std::vector<BeaconView>& beacons,
                                      const std::vector<ObjectView>& objects) {
  if (texture.id() == nullptr || texture.width() <= 0) {
    ImGui::TextDisabled("No camera image yet.");
    return std::nullopt;
  }
  const float scale = width / static_cast<float>(texture.width());
  const ImVec2 size(width, texture.height() * scale);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::Image(texture.id(), size);
  // A region: the objects' click targets lie on it.
  WidgetRegistry::ForThisThread().AddLastRegion(id);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  std::optional<std::string> clicked;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const float radius = std::max(10.0f, 0.05f * width);
  for (const ObjectView& object : objects) {
    if (!object.located) continue;
    const ImVec2 at(origin.x + object.pixel_x * scale, origin.y + object.pixel_y * scale);
    const bool hovered = std::hypot(mouse.x - at.x, mouse.y - at.y) < radius;
    draw->AddCircle(at, radius,
                    hovered ? IM_COL32(255, 255, 255, 255) : IM_COL32(255, 255, 255, 140), 32,
                    hovered ? 3.0f : 1.5f);
    // On a dark backdrop: a white name on the white plate could not be read.
    const ImVec2 name_at(at.x + radius + 4, at.y - 8);
    const ImVec2 name_size = ImGui::CalcTextSize(object.name.c_str());
    draw->AddRectFilled(ImVec2(name_at.x - 2, name_at.y),
                        ImVec2(name_at.x + name_size.x + 2, name_at.y + name_size.y),
                        IM_COL32(0, 0, 0, 120), 3.0f);
    draw->AddText(name_at, IM_COL32(255, 255, 255, 230), object.name.c_str());
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) clicked = object.name;
    // Registered so the test driver can click an object by name, as a teacher clicks the plate.
    ImGui::SetCursorScreenPos(ImVec2(at.x - radius, at.y - radius));
    ImGui::InvisibleButton((std::string("object:") + object.name).c_str(),
                           ImVec2(2 * radius, 2 * radius));
    if (ImGui::IsItemClicked()) clicked = object.name;
    WidgetRegistry::ForThisThread().AddLastItem((std::string("object:") + object.name).c_str());
  }
  for (const BeaconView& beacon : beacons) {
    if (!beacon.pixel) continue;
    const ImVec2 at(origin.x + (*beacon.pixel)[0] * scale, origin.y + (*beacon.pixel)[1] * scale);
    const ImU32 colour = IM_COL32(230, 159, 0, 255);  // Okabe-Ito orange, the beacon colour
    draw->AddCircle(at, 0.6f * radius, colour, 32, 3.0f);
    draw->AddCircleFilled(at, 3.0f, colour);
    // Centred under the marker: an object's name is written to its right, and a beacon sits on
    // an object, so beside it the two labels would overlap.
    const std::string label = beacon.label.empty() ? "beacon " + beacon.name : beacon.label;
    const ImVec2 label_size = ImGui::CalcTextSize(label.c_str());
    const ImVec2 label_at(at.x - 0.5f * label_size.x, at.y + 0.6f * radius + 4);
    draw->AddRectFilled(ImVec2(label_at.x - 2, label_at.y),
                        ImVec2(label_at.x + label_size.x + 2, label_at.y + label_size.y),
                        IM_COL32(0, 0, 0, 120), 3.0f);
    draw->AddText(label_at, colour, label.c_str());
  }
  ImGui::SetCursorScreenPos(ImVec2(origin.x, origin.y + size.y + ImGui::GetStyle().ItemSpacing.y));
  ImGui::Dummy(ImVec2(0, 0));
  return clicked;
}

}  // namespace recon::ui
