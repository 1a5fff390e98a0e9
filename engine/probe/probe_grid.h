#pragma once

// The table places a probe moves an object to: the centres of a grid over the world's table,
// checked against the table's extent, less the places where the object would overlap another.

#include <array>
#include <map>
#include <string>
#include <vector>

#include "engine/worlds/world.h"

namespace recon::probe {

/// The places an object is moved to: the centres of an nx x ny grid over `area`'s table (or the
/// part given), skipping places where the object would overlap another.
struct ProbeGrid {
  int nx = 10, ny = 10;
  /// x_min, x_max, y_min, y_max (metres); all zero: the world's whole placeable area.
  std::array<double, 4> bounds = {0, 0, 0, 0};
};

/// One place of the grid an object can go to.
struct GridPlace {
  int cell = 0;                       ///< row-major from y_min: iy * nx + ix
  std::array<double, 2> xy = {0, 0};  ///< table x, y (metres)
  double motion_m = 0;                ///< how far from where the scene had the object
};

/// The grid's bounds on `area`: UserError for fewer than 2 x 2 or more than 100 x 100 places,
/// or bounds that are not finite, are empty or leave the table (naming its extent).
std::array<double, 4> GridBounds(const ProbeGrid& grid, const worlds::ObjectArea& area);

/// The places of `grid` (within `bounds`) where `object` overlaps no other object of `layout`.
std::vector<GridPlace> FreePlaces(const ProbeGrid& grid, const std::array<double, 4>& bounds,
                                  const worlds::ObjectArea& area,
                                  const std::map<std::string, std::array<double, 2>>& layout,
                                  const std::string& object);

/// The objects to probe: `asked` once each in the order asked (every object of `layout` when
/// empty). UserError naming the valid objects for one the world does not have.
std::vector<std::string> ObjectsToProbe(const worlds::World& world,
                                        const std::map<std::string, std::array<double, 2>>& layout,
                                        const std::vector<std::string>& asked);

/// The world's table, checked: UserError when it cannot move its objects.
worlds::ObjectArea TableOf(const worlds::World& world);

}  // namespace recon::probe
