#pragma once

// The table places a probe moves an object to: the centres of a grid over the world's table,
// checked against the table's extent, less the places where the object would overlap another.

#include <array>
#include <cstdint>
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

/// The places of `grid` (within `bounds`) where `object` overlaps no other object of `layout`.
std::vector<GridPlace> FreePlaces(const ProbeGrid& grid, const std::array<double, 4>& bounds,
                                  const worlds::ObjectArea& area,
                                  const std::map<std::string, std::array<double, 2>>& layout,
                                  const std::string& object);

/// What every probe starts from: the world's table, the grid's bounds on it, the scene's layout
/// and the objects to move.
struct ProbedScene {
  worlds::ObjectArea area;
  std::array<double, 4> bounds = {0, 0, 0, 0};
  std::map<std::string, std::array<double, 2>> layout;
  std::vector<std::string> objects;
};

/// Resets `world` to `scene_seed` and checks everything a probe needs before it renders.
/// UserError when the world cannot move its objects, when there is no subject (`subjects` 0),
/// for fewer than 2 x 2 or more than 100 x 100 places, for bounds that are not finite, are empty
/// or leave the table (naming its extent), or for an object the world does not have (naming the
/// valid ones). `objects` are taken once each in the order asked; all of the scene's when empty.
ProbedScene SetUpProbe(worlds::World& world, uint64_t scene_seed,
                       const std::vector<std::string>& objects, const ProbeGrid& grid,
                       size_t subjects);

}  // namespace recon::probe
