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
  /// The rectangle of the widget labelled `label` in the last frame: its full ImGui label
  /// ("Delete##demo_3") if one matches, else the first whose visible label ("Delete") does.
  std::optional<WidgetRect> Find(const std::string& label) const;
  /// Every label drawn in the last frame, for error messages ("no widget 'Recrod'; drawn: ...").
  std::vector<std::string> Labels() const;

 private:
  struct Entry {
    std::string full_label;
    std::string visible_label;
    WidgetRect rect;
  };
  std::vector<Entry> widgets_;
};

/// The visible part of an ImGui label ("Start##record" -> "Start").
std::string VisibleLabel(const char* label);

}  // namespace recon::ui
