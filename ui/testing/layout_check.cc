#include "ui/testing/layout_check.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cmath>

#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

// Half a pixel either way is rounding, not a fault.
constexpr float kSlack = 1.0f;

bool Overlap(const WidgetRect& a, const WidgetRect& b) {
  return std::min(a.max_x, b.max_x) - std::max(a.min_x, b.min_x) > kSlack &&
         std::min(a.max_y, b.max_y) - std::max(a.min_y, b.min_y) > kSlack;
}

bool Contains(const WidgetRect& outer, const WidgetRect& inner) {
  return inner.min_x >= outer.min_x - kSlack && inner.min_y >= outer.min_y - kSlack &&
         inner.max_x <= outer.max_x + kSlack && inner.max_y <= outer.max_y + kSlack;
}

WidgetRect Intersect(const WidgetRect& a, const WidgetRect& b) {
  return {std::max(a.min_x, b.min_x), std::max(a.min_y, b.min_y), std::min(a.max_x, b.max_x),
          std::min(a.max_y, b.max_y), a.enabled};
}

bool Empty(const WidgetRect& r) { return r.max_x - r.min_x <= 0 || r.max_y - r.min_y <= 0; }

/// Windows the screens lay out: not tooltips, pop-ups or menus, which come and go over them.
bool LaidOut(const ImGuiWindow* w) {
  constexpr ImGuiWindowFlags kTransient =
      ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_Popup | ImGuiWindowFlags_ChildMenu;
  return w->Active && !w->Hidden && (w->Flags & kTransient) == 0;
}

void CheckWindows(std::vector<std::string>& faults) {
  const ImGuiContext& g = *GImGui;
  const ImVec2 display = g.IO.DisplaySize;
  for (const ImGuiWindow* w : g.Windows) {
    if (!LaidOut(w)) continue;
    const bool child = (w->Flags & ImGuiWindowFlags_ChildWindow) != 0;
    if (!child &&
        (w->Pos.x < -kSlack || w->Pos.y < -kSlack || w->Pos.x + w->Size.x > display.x + kSlack ||
         w->Pos.y + w->Size.y > display.y + kSlack)) {
      faults.push_back(
          Format("the panel '%s' (%.0f,%.0f %.0fx%.0f) lies outside the %.0fx%.0f window", w->Name,
                 w->Pos.x, w->Pos.y, w->Size.x, w->Size.y, display.x, display.y));
    }
    // A menu bar alone (the main menu bar) has no inner part to overflow.
    if ((w->Flags & ImGuiWindowFlags_MenuBar) != 0 && w->InnerRect.GetHeight() <= 0) continue;
    // Where the content ends, against where the panel's view ends. A child that its parent
    // shows only in part (the parent scrolls) ends where its own rectangle ends: what lies
    // beyond the parent's view is the parent's to scroll, and the parent is checked too (its
    // content includes the child).
    const float view_bottom =
        std::max(w->InnerClipRect.Max.y, std::floor(w->InnerRect.Max.y - w->WindowBorderSize));
    const float view_right = std::max(
        w->InnerClipRect.Max.x,
        w->InnerRect.Max.x - std::max(std::floor(w->WindowPadding.x * 0.5f), w->WindowBorderSize));
    const float below = w->DC.CursorMaxPos.y - view_bottom;
    const float right = w->DC.CursorMaxPos.x - view_right;
    if (below > kSlack && !w->ScrollbarY) {
      faults.push_back(Format("'%s': %.0f px of content below its bottom edge, and no scrollbar",
                              w->Name, below));
    }
    if (right > kSlack && !w->ScrollbarX) {
      faults.push_back(
          Format("'%s': %.0f px of content past its right edge, and no scrollbar", w->Name, right));
    }
  }
}

void CheckTables(std::vector<std::string>& faults) {
  ImGuiContext& g = *GImGui;
  for (int i = 0; i < g.Tables.GetMapSize(); ++i) {
    ImGuiTable* table = g.Tables.TryGetMapData(i);
    if (table == nullptr || table->LastFrameActive < g.FrameCount - 1) continue;
    for (int c = 0; c < table->ColumnsCount; ++c) {
      const ImGuiTableColumn& column = table->Columns[c];
      if (!column.IsEnabled) continue;
      const float content = std::max(
          {column.ContentMaxXFrozen, column.ContentMaxXUnfrozen, column.ContentMaxXHeadersIdeal});
      if (content > column.WorkMaxX + kSlack) {
        const char* name = ImGui::TableGetColumnName(table, c);
        faults.push_back(
            Format("table '%s' (in '%s'): column '%s' is %.0f px too narrow for its "
                   "content, which is cut",
                   table->OuterWindow != nullptr ? table->OuterWindow->Name : "?",
                   table->InnerWindow != nullptr ? table->InnerWindow->Name : "?",
                   name != nullptr ? name : "", content - column.WorkMaxX));
      }
    }
  }
}

void CheckWidgets(const WidgetRegistry& registry, std::vector<std::string>& faults) {
  const std::vector<WidgetPlacement>& widgets = registry.Placements();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const WidgetRect screen{0, 0, display.x, display.y, true};
  for (const WidgetPlacement& w : widgets) {
    const WidgetRect& r = w.rect;
    const WidgetRect& view = w.panel_view;
    // Beyond its panel's view by more than scrolling can bring in.
    const float left = view.min_x - r.min_x, right = r.max_x - view.max_x;
    const float up = view.min_y - r.min_y, down = r.max_y - view.max_y;
    if (left > kSlack + w.scroll_left || right > kSlack + w.scroll_right ||
        up > kSlack + w.scroll_up || down > kSlack + w.scroll_down) {
      faults.push_back(
          Format("'%s' lies out of view in '%s' (%.0f,%.0f-%.0f,%.0f; the view "
                 "%.0f,%.0f-%.0f,%.0f), and scrolling cannot bring it in",
                 w.label.c_str(), w.panel.c_str(), r.min_x, r.min_y, r.max_x, r.max_y, view.min_x,
                 view.min_y, view.max_x, view.max_y));
      continue;
    }
    // Cut by something narrower than its panel (a table's column): no scrolling helps. A
    // region may span columns (a table's row).
    if (w.region) continue;
    const bool cut_right = r.max_x > w.clip.max_x + kSlack && w.clip.max_x < view.max_x - kSlack;
    const bool cut_left = r.min_x < w.clip.min_x - kSlack && w.clip.min_x > view.min_x + kSlack;
    if (cut_right || cut_left) {
      faults.push_back(
          Format("'%s' is cut by its column in '%s'", w.label.c_str(), w.panel.c_str()));
    }
  }
  // On top of each other: compared where they are seen, so that rows scrolled out of a table's
  // view do not collide with what lies beyond the table.
  for (size_t i = 0; i < widgets.size(); ++i) {
    const WidgetPlacement& a = widgets[i];
    const WidgetRect seen_a = Intersect(Intersect(a.rect, a.panel_view), screen);
    if (Empty(seen_a)) continue;
    for (size_t j = i + 1; j < widgets.size(); ++j) {
      const WidgetPlacement& b = widgets[j];
      const WidgetRect seen_b = Intersect(Intersect(b.rect, b.panel_view), screen);
      if (Empty(seen_b) || !Overlap(seen_a, seen_b)) continue;
      const bool nested =
          (a.region && Contains(seen_a, seen_b)) || (b.region && Contains(seen_b, seen_a));
      if (nested) continue;
      faults.push_back(Format("'%s' (%.0f,%.0f-%.0f,%.0f) and '%s' (%.0f,%.0f-%.0f,%.0f) overlap",
                              a.label.c_str(), a.rect.min_x, a.rect.min_y, a.rect.max_x,
                              a.rect.max_y, b.label.c_str(), b.rect.min_x, b.rect.min_y,
                              b.rect.max_x, b.rect.max_y));
    }
  }
}

}  // namespace

std::vector<std::string> LayoutFaults(const WidgetRegistry& registry) {
  std::vector<std::string> faults;
  CheckWindows(faults);
  CheckTables(faults);
  CheckWidgets(registry, faults);
  return faults;
}

}  // namespace recon::ui
