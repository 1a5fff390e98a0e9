#pragma once

// A heat map over the table: one value per grid cell (the distractor probe's action change with
// an object moved there), with the objects' places marked.

#include <string>
#include <vector>

namespace recon::report {

struct HeatMap {
  std::string title;
  std::string subtitle;
  std::string value_label;  ///< the colour bar's, e.g. "action change (rad/s)"
  std::string x_label = "table x (m)", y_label = "table y (m)";
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  int nx = 0, ny = 0;
  /// nx * ny values, row-major, rows from y_min up; NaN cells (not measured) are drawn blank.
  std::vector<double> values;
  /// The colour scale's top; 0: the largest value. Maps sharing it compare by colour.
  double scale_max = 0;
  /// Drawn as seen from behind the robot at the table's near edge: x away from the robot (up),
  /// y to its left (so y grows leftwards); otherwise x to the right and y up.
  bool robot_view = false;
  struct Marker {
    double x = 0, y = 0;
    std::string label;
  };
  std::vector<Marker> markers;
};

/// Writes the heat map to `path` (.png or .svg) atomically. UserError for values that do not
/// fill the grid, an empty range or an unusable size.
void WriteChart(const HeatMap& map, const std::string& path, int width = 720, int height = 560);

}  // namespace recon::report
