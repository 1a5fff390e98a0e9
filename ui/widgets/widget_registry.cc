#include "ui/widgets/widget_registry.h"

#include <imgui.h>

#include <cstring>

namespace recon::ui {

WidgetRegistry& WidgetRegistry::ForThisThread() {
  thread_local WidgetRegistry registry;
  return registry;
}

void WidgetRegistry::BeginFrame() { widgets_.clear(); }

void WidgetRegistry::AddLastItem(const char* label, bool enabled) {
  const ImVec2 min = ImGui::GetItemRectMin();
  const ImVec2 max = ImGui::GetItemRectMax();
  widgets_.push_back({label, VisibleLabel(label), WidgetRect{min.x, min.y, max.x, max.y, enabled}});
}

std::optional<WidgetRect> WidgetRegistry::Find(const std::string& label) const {
  for (const Entry& e : widgets_) {
    if (e.full_label == label) return e.rect;
  }
  for (const Entry& e : widgets_) {
    if (e.visible_label == label) return e.rect;
  }
  return std::nullopt;
}

std::vector<std::string> WidgetRegistry::Labels() const {
  std::vector<std::string> labels;
  for (const Entry& e : widgets_) labels.push_back(e.full_label);
  return labels;
}

std::string VisibleLabel(const char* label) {
  const char* hidden = std::strstr(label, "##");
  return hidden == nullptr ? std::string(label) : std::string(label, hidden);
}

}  // namespace recon::ui
