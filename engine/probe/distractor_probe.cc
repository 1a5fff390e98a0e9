#include "engine/probe/distractor_probe.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "engine/core/error.h"

namespace recon::probe {

namespace {

/// Cells nearer home than this say little per centimetre (a change over nothing): not averaged.
constexpr double kMinMotion_m = 0.02;
constexpr double kPer_m = 0.1;  // "per 10 cm"
/// Places rendered before the methods look at them: bounds the memory of a large grid.
constexpr size_t kChunk = 256;

double Distance(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    const double d = static_cast<double>(a[i]) - b[i];
    sum += d * d;
  }
  return std::sqrt(sum);
}

/// One method's running tally over the places of one object.
struct Tally {
  std::vector<float> home_action, home_features;
  double action_sum = 0, feature_sum = 0;
  int counted = 0;
};

/// Adds the places rendered in `xs`, `ys` (cells[r], motion_m[r] of row r) to `probe` and `tally`.
void Measure(const ProbeSubject& subject, const ProbeSubject::Rows& xs,
             const ProbeSubject::Rows& ys, const std::vector<int>& cells,
             const std::vector<double>& motion_m, ObjectProbe& probe, Tally& tally) {
  if (xs.empty()) return;
  const ProbeSubject::Rows actions = subject.act(xs, ys);
  const ProbeSubject::Rows features = subject.features(xs, ys);
  for (size_t r = 0; r < cells.size(); ++r) {
    const size_t cell = static_cast<size_t>(cells[r]);
    probe.action_change[cell] = Distance(actions[r], tally.home_action);
    probe.feature_change[cell] = Distance(features[r], tally.home_features);
    if (motion_m[r] < kMinMotion_m) continue;
    tally.action_sum += probe.action_change[cell] / motion_m[r] * kPer_m;
    tally.feature_sum += probe.feature_change[cell] / motion_m[r] * kPer_m;
    ++tally.counted;
  }
}

}  // namespace

ProbeResult ProbeObjects(worlds::World& world, uint64_t scene_seed,
                         const std::vector<std::string>& objects, const ProbeGrid& grid,
                         const std::vector<ProbeSubject>& subjects, const ProbeProgress& progress,
                         const std::atomic<bool>* cancel) {
  const ProbedScene scene = SetUpProbe(world, scene_seed, objects, grid, subjects.size());
  const std::array<double, 4>& bounds = scene.bounds;
  const std::map<std::string, std::array<double, 2>>& layout = scene.layout;
  ProbeResult result;
  result.scene_seed = scene_seed;
  result.objects = scene.objects;
  for (const ProbeSubject& s : subjects) {
    result.methods.push_back(s.method);
    result.labels.push_back(s.label);
  }
  result.probes.assign(subjects.size(), {});
  const int total = static_cast<int>(result.objects.size()) * grid.nx * grid.ny;
  int done = 0;
  for (const std::string& object : result.objects) {
    world.Reset(scene_seed);
    const std::array<double, 2> home = layout.at(object);
    const worlds::Observation seen = world.Observe();
    ObjectProbe empty;
    empty.object = object;
    empty.home = home;
    empty.bounds = bounds;
    empty.nx = grid.nx;
    empty.ny = grid.ny;
    const size_t n = static_cast<size_t>(grid.nx) * grid.ny;
    empty.action_change.assign(n, std::numeric_limits<double>::quiet_NaN());
    empty.feature_change.assign(n, std::numeric_limits<double>::quiet_NaN());
    std::vector<ObjectProbe> probes(subjects.size(), empty);
    std::vector<Tally> tallies(subjects.size());
    for (size_t m = 0; m < subjects.size(); ++m) {
      tallies[m].home_action = subjects[m].act({seen.x}, {seen.y}).front();
      tallies[m].home_features = subjects[m].features({seen.x}, {seen.y}).front();
    }
    // Places are rendered and measured a chunk at a time: memory stays bounded whatever the grid.
    ProbeSubject::Rows xs, ys;
    std::vector<int> cells;
    std::vector<double> motion_m;
    const auto measure = [&] {
      for (size_t m = 0; m < subjects.size(); ++m) {
        Measure(subjects[m], xs, ys, cells, motion_m, probes[m], tallies[m]);
      }
      xs.clear();
      ys.clear();
      cells.clear();
      motion_m.clear();
    };
    const std::vector<GridPlace> places = FreePlaces(grid, bounds, scene.area, layout, object);
    size_t next = 0;
    for (int cell = 0; cell < grid.nx * grid.ny; ++cell) {
      if (cancel != nullptr && cancel->load()) throw ProbeCancelled{};
      if (next < places.size() && places[next].cell == cell) {
        const GridPlace& place = places[next++];
        world.PlaceObject(object, place.xy);
        const worlds::Observation moved = world.Observe();
        xs.push_back(moved.x);
        ys.push_back(moved.y);
        cells.push_back(place.cell);
        motion_m.push_back(place.motion_m);
        if (xs.size() >= kChunk) measure();
      }
      if (progress) progress(++done, total);
    }
    measure();
    for (size_t m = 0; m < subjects.size(); ++m) {
      const Tally& t = tallies[m];
      if (t.counted > 0) {
        probes[m].action_change_per_10cm = t.action_sum / t.counted;
        probes[m].feature_change_per_10cm = t.feature_sum / t.counted;
      }
      result.probes[m].push_back(std::move(probes[m]));
    }
  }
  world.Reset(scene_seed);  // the scene as it was
  return result;
}

}  // namespace recon::probe
