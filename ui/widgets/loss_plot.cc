#include "ui/widgets/loss_plot.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/widgets/widgets.h"

namespace recon::ui {

void PlotRange::Include(const std::vector<float>& values) {
  for (float v : values) {
    if (!std::isfinite(v)) continue;
    low = any ? std::min(low, v) : v;
    high = any ? std::max(high, v) : v;
    any = true;
  }
}

void LossPlot(const char* id, const std::string& title, const std::vector<float>& steps,
              const std::vector<float>& values, const PlotRange& range, float width, float height) {
  ImGui::PushID(id);
  ImGui::TextUnformatted(title.c_str());
  const float tick_width = ImGui::CalcTextSize("-00.00").x + 6;
  const float line = ImGui::GetTextLineHeight();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 top_left(origin.x + tick_width, origin.y + line * 0.5f);
  const ImVec2 bottom_right(origin.x + width, origin.y + height - line * 1.5f);
  ImGui::Dummy(ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImU32 frame = ImGui::GetColorU32(ImGuiCol_Border);
  const ImU32 grid = ImGui::GetColorU32(ImGuiCol_Border, 0.4f);
  const ImU32 text = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  draw->AddRectFilled(top_left, bottom_right, ImGui::GetColorU32(ImGuiCol_FrameBg));
  draw->AddRect(top_left, bottom_right, frame);
  if (values.empty() || !range.any) {
    draw->AddText(ImVec2(top_left.x + 8, top_left.y + 8), text, "no data yet");
    ImGui::PopID();
    return;
  }
  // A flat curve still gets a scale around its value.
  const float pad = range.high > range.low ? 0.0f : 0.5f;
  const float low = range.low - pad, high = range.high + pad;
  const auto y_of = [&](float v) {
    return bottom_right.y - (v - low) / (high - low) * (bottom_right.y - top_left.y);
  };
  // Three ticks: the shared range's ends and middle.
  for (const float v : {low, 0.5f * (low + high), high}) {
    const float y = y_of(v);
    draw->AddLine(ImVec2(top_left.x, y), ImVec2(bottom_right.x, y), grid);
    const std::string label = Format("%.3g", v);
    draw->AddText(ImVec2(origin.x, y - line * 0.5f), text, label.c_str());
  }
  const float first = steps.empty() ? 0 : steps.front();
  const float last = steps.empty() ? 1 : std::max(steps.back(), first + 1);
  const auto x_of = [&](size_t i) {
    const float step = i < steps.size() ? steps[i] : static_cast<float>(i);
    return top_left.x + (step - first) / (last - first) * (bottom_right.x - top_left.x);
  };
  std::vector<ImVec2> points;
  points.reserve(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) continue;
    points.emplace_back(x_of(i), std::clamp(y_of(values[i]), top_left.y, bottom_right.y));
  }
  draw->AddPolyline(points.data(), static_cast<int>(points.size()),
                    ImGui::GetColorU32(ImGuiCol_PlotLines), ImDrawFlags_None, 1.5f);
  // The step axis: where the curve starts and ends.
  const float axis_y = bottom_right.y + 2;
  const std::string from = Format("step %.0f", first);
  const std::string to = Format("%.0f", steps.empty() ? 0.0f : steps.back());
  draw->AddText(ImVec2(top_left.x, axis_y), text, from.c_str());
  draw->AddText(ImVec2(bottom_right.x - ImGui::CalcTextSize(to.c_str()).x, axis_y), text,
                to.c_str());
  ImGui::PopID();
}

}  // namespace recon::ui
