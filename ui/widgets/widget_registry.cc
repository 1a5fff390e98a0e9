#include "ui/widgets/widget_registry.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cstring>

namespace recon::ui {

namespace {

WidgetRect RectOf(const ImRect& r) { return {r.Min.x, r.Min.y, r.Max.x, r.Max.y, true}; }

}  // namespace

WidgetRegistry& WidgetRegistry::ForThisThread() {
  thread_local WidgetRegistry registry;
  return registry;
}

void WidgetRegistry::BeginFrame() { widgets_.clear(); }

namespace {

WidgetRect LastItemRect(bool enabled) {
  const ImVec2 min = ImGui::GetItemRectMin();
  const ImVec2 max = ImGui::GetItemRectMax();
  return {min.x, min.y, max.x, max.y, enabled};
}

}  // namespace

void WidgetRegistry::AddLastItem(const char* label, bool enabled) {
  Add(label, LastItemRect(enabled), false);
}

void WidgetRegistry::AddLastRegion(const char* label, bool enabled) {
  Add(label, LastItemRect(enabled), true);
}

void WidgetRegistry::AddRegion(const char* label, const WidgetRect& rect) {
  Add(label, rect, true);
}

void WidgetRegistry::Add(const char* label, const WidgetRect& rect, bool region) {
  WidgetPlacement p;
  p.label = label;
  p.visible_label = VisibleLabel(label);
  p.rect = rect;
  p.region = region;
  const ImGuiWindow* window = ImGui::GetCurrentWindow();
  p.panel = window->Name;
  // A menu bar's items lie in the bar, above the window's inner part.
  p.panel_view = RectOf(window->DC.NavLayerCurrent == ImGuiNavLayer_Menu ? window->MenuBarRect()
                                                                         : window->InnerClipRect);
  p.clip = RectOf(window->ClipRect);
  // A child panel scrolls within its parent: a widget out of both views is reachable when the
  // two can scroll far enough together.
  for (const ImGuiWindow* w = window; w != nullptr; w = w->ParentWindow) {
    if (w->ScrollbarX) {
      p.scroll_left += w->Scroll.x;
      p.scroll_right += std::max(0.0f, w->ScrollMax.x - w->Scroll.x);
    }
    if (w->ScrollbarY) {
      p.scroll_up += w->Scroll.y;
      p.scroll_down += std::max(0.0f, w->ScrollMax.y - w->Scroll.y);
    }
    if ((w->Flags & ImGuiWindowFlags_ChildWindow) == 0) break;
  }
  widgets_.push_back(std::move(p));
}

std::optional<WidgetRect> WidgetRegistry::Find(const std::string& label) const {
  const std::optional<WidgetPlacement> p = FindPlacement(label);
  if (!p) return std::nullopt;
  return p->rect;
}

std::optional<WidgetPlacement> WidgetRegistry::FindPlacement(const std::string& label) const {
  for (const WidgetPlacement& w : widgets_) {
    if (w.label == label) return w;
  }
  for (const WidgetPlacement& w : widgets_) {
    if (w.visible_label == label) return w;
  }
  return std::nullopt;
}

std::vector<std::string> WidgetRegistry::Labels() const {
  std::vector<std::string> labels;
  for (const WidgetPlacement& w : widgets_) {
    if (!w.region) labels.push_back(w.label);
  }
  return labels;
}

std::string VisibleLabel(const char* label) {
  const char* hidden = std::strstr(label, "##");
  return hidden == nullptr ? std::string(label) : std::string(label, hidden);
}

}  // namespace recon::ui
