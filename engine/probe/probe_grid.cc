#include "engine/probe/probe_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/core/error.h"

namespace recon::probe {

namespace {

constexpr int kMaxGridSide = 100;

std::string Metres(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", v);
  return text;
}

std::array<double, 4> GridBounds(const ProbeGrid& grid, const worlds::ObjectArea& area) {
  if (grid.nx < 2 || grid.ny < 2 || grid.nx > kMaxGridSide || grid.ny > kMaxGridSide) {
    throw UserError("a probe grid has 2 to " + std::to_string(kMaxGridSide) +
                    " places per side, got " + std::to_string(grid.nx) + " x " +
                    std::to_string(grid.ny));
  }
  const std::array<double, 4> table = {area.x_min, area.x_max, area.y_min, area.y_max};
  const std::array<double, 4>& b = grid.bounds;
  if (b == std::array<double, 4>{0, 0, 0, 0}) return table;
  for (double v : b) {
    if (!std::isfinite(v)) throw UserError("the probe grid's bounds must be finite numbers");
  }
  if (!(b[0] < b[1]) || !(b[2] < b[3])) {
    throw UserError("the probe grid's bounds are empty: x from " + Metres(b[0]) + " to " +
                    Metres(b[1]) + ", y from " + Metres(b[2]) + " to " + Metres(b[3]));
  }
  constexpr double kSlack_m = 1e-9;
  if (b[0] < table[0] - kSlack_m || b[1] > table[1] + kSlack_m || b[2] < table[2] - kSlack_m ||
      b[3] > table[3] + kSlack_m) {
    throw UserError("the probe grid leaves the table: objects go at x " + Metres(table[0]) +
                    " to " + Metres(table[1]) + " m and y " + Metres(table[2]) + " to " +
                    Metres(table[3]) + " m");
  }
  return b;
}

std::vector<std::string> ObjectsToProbe(const worlds::World& world,
                                        const std::map<std::string, std::array<double, 2>>& layout,
                                        const std::vector<std::string>& asked) {
  std::vector<std::string> objects;
  for (const std::string& object : asked) {  // each once, in the order asked
    if (std::find(objects.begin(), objects.end(), object) == objects.end()) {
      objects.push_back(object);
    }
  }
  if (objects.empty()) {
    for (const auto& [name, place] : layout) objects.push_back(name);
  }
  for (const std::string& object : objects) {
    if (!layout.count(object)) {
      std::string names;
      for (const auto& [name, place] : layout) names += (names.empty() ? "" : ", ") + name;
      throw UserError("the " + world.Name() + " world has no object \"" + object +
                      "\" (valid: " + names + ")");
    }
  }
  return objects;
}

}  // namespace

std::vector<GridPlace> FreePlaces(const ProbeGrid& grid, const std::array<double, 4>& bounds,
                                  const worlds::ObjectArea& area,
                                  const std::map<std::string, std::array<double, 2>>& layout,
                                  const std::string& object) {
  const auto radius = [&](const std::string& name) {
    const auto found = area.radius_m.find(name);
    return found == area.radius_m.end() ? 0.0 : found->second;
  };
  const std::array<double, 2> home = layout.at(object);
  std::vector<GridPlace> places;
  for (int iy = 0; iy < grid.ny; ++iy) {
    for (int ix = 0; ix < grid.nx; ++ix) {
      const std::array<double, 2> xy = {bounds[0] + (ix + 0.5) * (bounds[1] - bounds[0]) / grid.nx,
                                        bounds[2] + (iy + 0.5) * (bounds[3] - bounds[2]) / grid.ny};
      bool overlaps = false;
      for (const auto& [other, where] : layout) {
        if (other == object) continue;
        overlaps |= std::hypot(xy[0] - where[0], xy[1] - where[1]) < radius(object) + radius(other);
      }
      if (!overlaps) {
        places.push_back({iy * grid.nx + ix, xy, std::hypot(xy[0] - home[0], xy[1] - home[1])});
      }
    }
  }
  return places;
}

ProbedScene SetUpProbe(worlds::World& world, uint64_t scene_seed,
                       const std::vector<std::string>& objects, const ProbeGrid& grid,
                       size_t subjects) {
  const std::optional<worlds::ObjectArea> area = world.PlaceableArea();
  if (!area) {
    throw UserError("the probe moves objects over a table, which the " + world.Name() +
                    " world cannot do (the simulated cell's tabletop can)");
  }
  if (subjects == 0) throw UserError("the probe needs a trained method to probe");
  ProbedScene scene;
  scene.area = *area;
  scene.bounds = GridBounds(grid, scene.area);
  world.Reset(scene_seed);
  scene.layout = world.ObjectLayout();
  scene.objects = ObjectsToProbe(world, scene.layout, objects);
  return scene;
}

}  // namespace recon::probe
