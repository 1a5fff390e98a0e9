#include "engine/probe/recorded_readout.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace recon::probe {

namespace {

/// An object whose episodes' mean readings all lie within this (the beacons' unit, metres on a
/// cell) never moved: there is nothing to read out.
constexpr double kStill = 0.01;
constexpr int kFold = 4;
/// One frame as recorded: its observation, beacon reading and episode.
struct Frame {
  const std::vector<float>*x, *y, *b;
  int episode;
};

bool StoodStill(const std::vector<std::vector<double>>& readings, const std::vector<int>& episodes,
                int episode_count) {
  const size_t dims = readings.empty() ? 0 : readings.front().size();
  for (size_t d = 0; d < dims; ++d) {
    std::vector<double> sum(static_cast<size_t>(episode_count), 0.0);
    std::vector<int> count(static_cast<size_t>(episode_count), 0);
    for (size_t i = 0; i < readings.size(); ++i) {
      sum[static_cast<size_t>(episodes[i])] += readings[i][d];
      ++count[static_cast<size_t>(episodes[i])];
    }
    double lo = INFINITY, hi = -INFINITY;
    for (size_t e = 0; e < sum.size(); ++e) {
      if (count[e] == 0) continue;
      lo = std::min(lo, sum[e] / count[e]);
      hi = std::max(hi, sum[e] / count[e]);
    }
    if (hi - lo > kStill) return false;
  }
  return true;
}

}  // namespace

RecordedFrames SampleRecordedFrames(const Dataset& data, const std::vector<BeaconSpec>& beacons,
                                    const std::vector<std::string>& objects, int max_frames) {
  if (objects.size() != beacons.size()) {
    throw UserError("a read-out needs the object of each of the " + std::to_string(beacons.size()) +
                    " beacons, got " + std::to_string(objects.size()));
  }
  std::vector<Frame> all;
  int episode = 0;
  for (const Episode& demo : data.demos) {
    for (const Sample& s : demo.samples) all.push_back({&s.x, &s.y, &s.b, episode});
    ++episode;
  }
  // Play chunks are episodes too; a play sample of no known chunk stands alone.
  size_t next = 0;
  for (int size : data.play_chunks) {
    for (int j = 0; j < size && next < data.play.size(); ++j, ++next) {
      const PlaySample& s = data.play[next];
      all.push_back({&s.x, &s.y, &s.b, episode});
    }
    ++episode;
  }
  for (; next < data.play.size(); ++next) {
    const PlaySample& s = data.play[next];
    all.push_back({&s.x, &s.y, &s.b, episode++});
  }
  RecordedFrames frames;
  frames.episode_count = episode;
  const size_t dim = static_cast<size_t>(TotalBeaconDim(beacons));
  const size_t keep = std::min(all.size(), static_cast<size_t>(std::max(0, max_frames)));
  for (size_t k = 0; k < keep; ++k) {
    const Frame& f = all[k * all.size() / keep];  // evenly strided over every episode
    if (f.b->size() != dim) {
      throw UserError("a recorded frame's beacon reading has " + std::to_string(f.b->size()) +
                      " numbers, the session's beacons " + std::to_string(dim));
    }
    frames.xs.push_back(*f.x);
    frames.ys.push_back(*f.y);
    frames.episodes.push_back(f.episode);
    size_t at = 0;
    for (size_t i = 0; i < beacons.size(); ++i) {
      const size_t n = static_cast<size_t>(beacons[i].dim);
      frames.readings[objects[i]].emplace_back(f.b->begin() + static_cast<std::ptrdiff_t>(at),
                                               f.b->begin() + static_cast<std::ptrdiff_t>(at + n));
      at += n;
    }
  }
  return frames;
}

std::map<std::string, std::optional<ReadoutScore>> ReadOutRecorded(const ProbeSubject& subject,
                                                                   const RecordedFrames& frames) {
  std::map<std::string, std::optional<ReadoutScore>> scores;
  if (frames.xs.empty()) return scores;
  // Every fold must hold some episodes out and fit on at least two others.
  const bool splits = frames.episode_count >= 2 * kFold;
  ProbeSubject::Rows features;
  if (splits) features = subject.features(frames.xs, frames.ys);
  for (const auto& [object, readings] : frames.readings) {
    if (!splits || StoodStill(readings, frames.episodes, frames.episode_count)) {
      scores[object] = std::nullopt;
    } else {
      scores[object] = CrossValidatedReadout(features, readings, frames.episodes, kFold, 0);
    }
  }
  return scores;
}

}  // namespace recon::probe
