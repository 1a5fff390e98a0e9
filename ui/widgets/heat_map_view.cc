#include "ui/widgets/heat_map_view.h"

#include <imgui.h>

#include <array>
#include <cmath>

#include "engine/core/color_scale.h"
#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void HeatMapView(const char* id, const ProbeView::Map& map, float width) {
  const float x_min = map.bounds[0], x_max = map.bounds[1];
  const float y_min = map.bounds[2], y_max = map.bounds[3];
  if (map.nx < 1 || map.ny < 1 || !(x_max > x_min) || !(y_max > y_min) ||
      map.values.size() != static_cast<size_t>(map.nx) * static_cast<size_t>(map.ny)) {
    ImGui::TextDisabled("(no heat map)");
    return;
  }
  // To scale: the table's y across, its x up.
  const float height = width * (x_max - x_min) / (y_max - y_min);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const auto page = [&](float x, float y) {
    return ImVec2(origin.x + (y_max - y) / (y_max - y_min) * width,
                  origin.y + height - (x - x_min) / (x_max - x_min) * height);
  };
  const float cell_x = (x_max - x_min) / map.nx, cell_y = (y_max - y_min) / map.ny;
  const float top = map.scale_max > 0 ? map.scale_max : 1.0f;
  for (int iy = 0; iy < map.ny; ++iy) {
    for (int ix = 0; ix < map.nx; ++ix) {
      const float v = map.values[static_cast<size_t>(iy) * map.nx + ix];
      ImU32 colour = IM_COL32(237, 237, 237, 255);
      if (std::isfinite(v)) {
        const std::array<double, 3> c = SequentialColor(v / top);
        colour = IM_COL32(static_cast<int>(255 * c[0]), static_cast<int>(255 * c[1]),
                          static_cast<int>(255 * c[2]), 255);
      }
      const float x0 = x_min + ix * cell_x, y0 = y_min + iy * cell_y;
      const ImVec2 a = page(x0, y0), b = page(x0 + cell_x, y0 + cell_y);
      draw->AddRectFilled(ImVec2(std::fmin(a.x, b.x), std::fmin(a.y, b.y)),
                          ImVec2(std::fmax(a.x, b.x) + 0.5f, std::fmax(a.y, b.y) + 0.5f), colour);
    }
  }
  draw->AddRect(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(90, 90, 90, 255));
  for (const auto& [label, xy] : map.markers) {
    const ImVec2 at = page(xy[0], xy[1]);
    draw->AddCircleFilled(at, Px(4), IM_COL32(255, 255, 255, 255));
    draw->AddCircle(at, Px(4), IM_COL32(0, 0, 0, 255), 0, Px(1.5f));
    // On a dark plate so the label reads over bright and blank cells alike.
    const ImVec2 text_at(at.x + Px(7), at.y - ImGui::GetTextLineHeight() / 2);
    const ImVec2 size = ImGui::CalcTextSize(label.c_str());
    draw->AddRectFilled(ImVec2(text_at.x - Px(2), text_at.y),
                        ImVec2(text_at.x + size.x + Px(2), text_at.y + size.y),
                        IM_COL32(0, 0, 0, 170), Px(2));
    draw->AddText(text_at, IM_COL32(255, 255, 255, 255), label.c_str());
  }
  ImGui::Dummy(ImVec2(width, height));
  WidgetRegistry::ForThisThread().AddLastItem(id);
}

}  // namespace recon::ui
