#include "ui/widgets/height_gauge.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

constexpr float kTop_m = 0.30f;

}  // namespace

float GaugeOffset(float height_m, float height_px) {
  const float h = std::clamp(std::isfinite(height_m) ? height_m : 0.0f, 0.0f, kTop_m);
  return height_px * (1.0f - std::sqrt(h / kTop_m));
}

void HeightGauge(const char* id, float height_m, float grasp_min_m, float grasp_max_m,
                 float height_px) {
  const float bar = Px(16);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float left = origin.x + Px(4);
  draw->AddRectFilled(ImVec2(left, origin.y), ImVec2(left + bar, origin.y + height_px),
                      IM_COL32(60, 60, 66, 255), 3.0f);
  if (grasp_max_m > grasp_min_m) {
    // Okabe-Ito bluish green: where closing the gripper holds.
    draw->AddRectFilled(ImVec2(left, origin.y + GaugeOffset(grasp_max_m, height_px)),
                        ImVec2(left + bar, origin.y + GaugeOffset(grasp_min_m, height_px)),
                        IM_COL32(0, 158, 115, 255));
    draw->AddText(
        ImVec2(left + bar + Px(4), origin.y + GaugeOffset(grasp_max_m, height_px) - Px(7)),
        IM_COL32(0, 158, 115, 255), "grasp");
  }
  for (const float tick_cm : {1.0f, 2.0f, 5.0f, 10.0f, 20.0f, 30.0f}) {
    const float y = origin.y + GaugeOffset(tick_cm / 100.0f, height_px);
    draw->AddLine(ImVec2(left - Px(3), y), ImVec2(left, y), IM_COL32(200, 200, 200, 200));
    if (tick_cm >= 5.0f) {
      const std::string label = Format("%.0f", tick_cm);
      draw->AddText(ImVec2(left + bar + Px(4), y - Px(7)), IM_COL32(170, 170, 170, 255),
                    label.c_str());
    }
  }
  const float y = origin.y + GaugeOffset(height_m, height_px);
  draw->AddTriangleFilled(ImVec2(left - Px(6), y - Px(5)), ImVec2(left - Px(6), y + Px(5)),
                          ImVec2(left + bar + Px(2), y), IM_COL32(255, 216, 26, 255));
  ImGui::Dummy(ImVec2(bar + Px(48), height_px));
  WidgetRegistry::ForThisThread().AddLastItem(id);
  ImGui::TextUnformatted("cm");
}

}  // namespace recon::ui
