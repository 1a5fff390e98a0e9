#pragma once

#include <optional>
#include <string>
#include <vector>

namespace recon::ui {

/// A widget's rectangle on screen, in pixels.
struct WidgetRect {
  float min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  bool enabled = true;
  float CentreX() const { return (min_x + max_x) / 2; }
  float CentreY() const { return (min_y + max_y) / 2; }
};

/// Where a registered widget lies in the window's panels: what the layout checks
/// (ui/testing/layout_check.h) and the test driver's scrolling need.
struct WidgetPlacement {
  std::string label;          ///< the full ImGui label ("Delete##demo_3")
  std::string visible_label;  ///< what a person reads ("Delete")
  WidgetRect rect;
  /// A part of the layout holding widgets (a column, a panel, a table), not one control: it may
  /// hold others, but must not lie partly over anything.
  bool region = false;
  std::string panel;      ///< the ImGui window it is drawn in (its name)
  WidgetRect panel_view;  ///< the part of that panel on screen
  WidgetRect clip;        ///< what clips it there (a table's column is narrower than its panel)
  /// How far scrolling the panel and the panels holding it can still move their content, in each
  /// direction (0 where no scrollbar is shown): a widget beyond the view by less is reachable.
  float scroll_left = 0, scroll_right = 0, scroll_up = 0, scroll_down = 0;
};

/// Where each labelled widget was drawn in the last frame. ImGui 1.86 has no test engine, so the
/// studio's widgets register themselves here by label, and the headless test driver clicks them
/// by that label, as a person would read it. One registry per UI thread.
class WidgetRegistry {
 public:
  static WidgetRegistry& ForThisThread();

  /// Called at the start of each frame: widgets not drawn again are forgotten.
  void BeginFrame();
  /// Records the last ImGui item under `label` (its visible part: "Record##demo" -> "Record").
  void AddLastItem(const char* label, bool enabled = true);
  /// Records the last ImGui item (a group, a child panel, a table just ended) as a region of the
  /// layout: the layout checks find text that runs out of it into a neighbour.
  void AddLastRegion(const char* label, bool enabled = true);
  /// Records a region whose rectangle is not the last item's (a selectable row, without the
  /// spacing ImGui gives its click target to close the gaps between rows).
  void AddRegion(const char* label, const WidgetRect& rect);
  /// The rectangle of the widget labelled `label` in the last frame: its full ImGui label
  /// ("Delete##demo_3") if one matches, else the first whose visible label ("Delete") does.
  std::optional<WidgetRect> Find(const std::string& label) const;
  /// Where the widget labelled `label` (matched as Find does) lies, if it was drawn.
  std::optional<WidgetPlacement> FindPlacement(const std::string& label) const;
  /// Every label drawn in the last frame, for error messages ("no widget 'Recrod'; drawn: ...").
  std::vector<std::string> Labels() const;
  /// Every widget and region drawn in the last frame, in drawing order.
  const std::vector<WidgetPlacement>& Placements() const { return widgets_; }

 private:
  void Add(const char* label, const WidgetRect& rect, bool region);

  std::vector<WidgetPlacement> widgets_;
};

/// The visible part of an ImGui label ("Start##record" -> "Start").
std::string VisibleLabel(const char* label);

}  // namespace recon::ui
