#include "engine/probe/feature_readout.h"

#include <algorithm>

namespace recon::probe {

namespace {

constexpr double kStill_m = 1e-3;

bool StandsStill(const std::vector<std::vector<double>>& positions) {
  for (size_t d = 0; d < 2; ++d) {
    double lo = positions.front()[d], hi = lo;
    for (const std::vector<double>& p : positions) {
      lo = std::min(lo, p[d]);
      hi = std::max(hi, p[d]);
    }
    if (hi - lo > kStill_m) return false;
  }
  return true;
}

}  // namespace

SceneFrames RenderScenes(worlds::World& world, const std::vector<uint64_t>& seeds,
                         const ProbeProgress& progress, const std::atomic<bool>* cancel) {
  SceneFrames frames;
  int done = 0;
  for (uint64_t seed : seeds) {
    if (cancel != nullptr && cancel->load()) throw ProbeCancelled{};
    world.Reset(seed);
    const worlds::Observation seen = world.Observe();
    frames.xs.push_back(seen.x);
    frames.ys.push_back(seen.y);
    for (const auto& [object, xy] : world.ObjectLayout()) {
      frames.positions[object].push_back({xy[0], xy[1]});
    }
    if (progress) progress(++done, static_cast<int>(seeds.size()));
  }
  return frames;
}

std::map<std::string, std::optional<ReadoutScore>> ReadOutObjects(const ProbeSubject& subject,
                                                                  const SceneFrames& frames) {
  std::map<std::string, std::optional<ReadoutScore>> scores;
  if (frames.xs.empty()) return scores;
  const ProbeSubject::Rows features = subject.features(frames.xs, frames.ys);
  for (const auto& [object, positions] : frames.positions) {
    scores[object] = StandsStill(positions)
                         ? std::nullopt
                         : std::make_optional(FitLinearReadout(features, positions));
  }
  return scores;
}

}  // namespace recon::probe
