#pragma once

// A toy world for the probe's tests, where the answers are known by construction: two objects,
// "red" and "blue", on a 1 m x 1 m table, drawn as 2 x 2 pixel squares on a black 20 x 20
// camera image; and a "policy" that reads only the red one (its action and its features are
// the red pixels' centroid).

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/probe/distractor_probe.h"
#include "engine/worlds/world.h"

namespace recon::probe::testing {

class TwoObjectWorld : public worlds::World {
 public:
  static constexpr int kSize = 20;

  std::string Name() const override { return "two-objects"; }
  DataSpec Spec() const override { return DataSpec{1, {3, kSize, kSize}, 0, 2}; }
  int EpisodeLength() const override { return 1; }
  void Reset(uint64_t seed) override {
    ++resets_;
    places_ = {{"red", {0.25, 0.25 + 0.01 * static_cast<double>(seed % 10)}},
               {"blue", {0.75, 0.75}}};
  }
  worlds::Observation Observe() const override {
    std::vector<float> y(3 * kSize * kSize, 0.0f);
    for (const auto& [name, place] : places_) {
      const int channel = name == "red" ? 0 : 2;
      const int row = std::clamp(static_cast<int>(place[1] * kSize), 0, kSize - 2);
      const int column = std::clamp(static_cast<int>(place[0] * kSize), 0, kSize - 2);
      for (int r = row; r < row + 2; ++r) {
        for (int c = column; c < column + 2; ++c) y[(channel * kSize + r) * kSize + c] = 255;
      }
    }
    return {{0.0f}, y};
  }
  void Step(const std::vector<float>&) override {}
  std::vector<float> ExpertAction() const override { return {0, 0}; }
  std::vector<float> BeaconReading() override { return {}; }
  PlaySample SamplePlay() override { return {}; }
  int PlaySamplesPerScenario() const override { return 0; }
  double EpisodeMetric() const override { return 0; }
  worlds::WorldTraits Traits() const override { return {}; }
  std::map<std::string, std::array<double, 2>> ObjectLayout() const override { return places_; }
  std::optional<worlds::ObjectArea> PlaceableArea() const override {
    worlds::ObjectArea area;
    area.x_min = area.y_min = 0.0;
    area.x_max = area.y_max = 1.0;
    area.radius_m = {{"red", 0.05}, {"blue", 0.05}};
    return area;
  }
  void PlaceObject(const std::string& object, const std::array<double, 2>& xy) override {
    if (!places_.count(object)) throw UserError("no object " + object);
    places_[object] = xy;
  }

  int resets() const { return resets_; }

 private:
  std::map<std::string, std::array<double, 2>> places_;
  int resets_ = 0;
};

/// Where the red pixels are (their centroid, in pixels): what a policy that reads only the red
/// object could act on.
inline std::vector<float> RedCentroid(const std::vector<float>& y) {
  constexpr int n = TwoObjectWorld::kSize;
  double sx = 0, sy = 0, count = 0;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (y[static_cast<size_t>(r) * n + c] > 128) {
        sx += c;
        sy += r;
        ++count;
      }
    }
  }
  return {static_cast<float>(sx / count), static_cast<float>(sy / count)};
}

inline ProbeSubject ReadsOnlyRed() {
  ProbeSubject subject;
  subject.method = "red-reader";
  subject.label = "Reads the red object";
  subject.act = [](const ProbeSubject::Rows&, const ProbeSubject::Rows& ys) {
    ProbeSubject::Rows out;
    for (const auto& y : ys) out.push_back(RedCentroid(y));
    return out;
  };
  subject.features = subject.act;
  return subject;
}

}  // namespace recon::probe::testing
