#pragma once

// Small synthetic datasets for the learner's tests.

#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/core/rng.h"
#include "engine/learn/learner.h"

namespace recon::learn::testing {

/// Vector task: y = [target xy, 4 distractor values], x = robot xy, b = target xy,
/// u = 0.5 * (target - robot). Learnable from y; the beacon names the relevant part of y.
inline Dataset MakeVectorTask(uint64_t seed, int episodes = 20, int play = 0) {
  Rng rng(seed);
  Dataset data;
  data.spec = DataSpec{2, {6}, 2, 2};
  for (int e = 0; e < episodes; ++e) {
    Episode episode;
    for (int t = 0; t < 5; ++t) {
      Sample s;
      for (int i = 0; i < 2; ++i) s.x.push_back(static_cast<float>(rng.Uniform(-1, 1)));
      for (int i = 0; i < 6; ++i) s.y.push_back(static_cast<float>(rng.Uniform(-1, 1)));
      s.b = {s.y[0], s.y[1]};
      s.u = {0.5f * (s.y[0] - s.x[0]), 0.5f * (s.y[1] - s.x[1])};
      episode.samples.push_back(s);
    }
    data.demos.push_back(episode);
  }
  for (int p = 0; p < play; ++p) {
    PlaySample s;
    for (int i = 0; i < 2; ++i) s.x.push_back(static_cast<float>(rng.Uniform(-1, 1)));
    for (int i = 0; i < 6; ++i) s.y.push_back(static_cast<float>(rng.Uniform(-1, 1)));
    s.b = {s.y[0], s.y[1]};
    data.play.push_back(s);
  }
  return data;
}

/// Mean squared error of the policy's actions against the demonstrations' actions.
inline double ActionMse(const Policy& policy, const Dataset& data) {
  double error = 0;
  int n = 0;
  for (const Episode& e : data.demos) {
    for (const Sample& s : e.samples) {
      const std::vector<float> u = policy.Act(s.x, s.y);
      for (size_t i = 0; i < u.size(); ++i, ++n) error += (u[i] - s.u[i]) * (u[i] - s.u[i]);
    }
  }
  return error / n;
}

/// Image task: C x size x size images with a noisy background (values in [225, 255]) and one
/// bright 2x2 block; b = block position in [-1, 1]^2, u = direction to it from x.
inline Dataset MakeImageTask(uint64_t seed, int samples = 24, int size = 16, int play = 0) {
  Rng rng(seed);
  Dataset data;
  data.spec = DataSpec{2, {3, size, size}, 2, 2};
  auto make = [&](std::vector<float>& x, std::vector<float>& y, std::vector<float>& b) {
    y.resize(3 * size * size);
    for (float& v : y) v = static_cast<float>(225 + rng.UniformInt(31));
    const int bx = static_cast<int>(rng.UniformInt(size - 1)),
              by = static_cast<int>(rng.UniformInt(size - 1));
    for (int c = 0; c < 3; ++c) {
      for (int i = bx; i < bx + 2; ++i) {
        for (int j = by; j < by + 2; ++j) y[(c * size + i) * size + j] = c == 1 ? 0.0f : 255.0f;
      }
    }
    b = {2.0f * bx / (size - 2) - 1.0f, 2.0f * by / (size - 2) - 1.0f};
    x = {static_cast<float>(rng.Uniform(-1, 1)), static_cast<float>(rng.Uniform(-1, 1))};
  };
  Episode episode;
  for (int i = 0; i < samples; ++i) {
    Sample s;
    make(s.x, s.y, s.b);
    s.u = {s.b[0] - s.x[0], s.b[1] - s.x[1]};
    episode.samples.push_back(s);
  }
  data.demos.push_back(episode);
  for (int p = 0; p < play; ++p) {
    PlaySample s;
    make(s.x, s.y, s.b);
    data.play.push_back(s);
  }
  return data;
}

/// A small CNN for 16x16 images, so that image tests run in milliseconds.
inline NetworkConfig SmallImageNet() {
  NetworkConfig n;
  n.conv_channels = {4, 8};
  n.conv_kernel = 3;
  n.cnn_hidden = {32};
  n.image_scale = 1.0f / 255.0f;
  return n;
}

/// Exact equality of two float vectors, NaN included (bitwise).
inline bool BitwiseEqual(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

/// A fingerprint of a policy's behaviour: its features and actions on the first samples.
inline std::vector<float> Probe(const Policy& policy, const Dataset& data, int count = 8) {
  std::vector<float> out;
  int n = 0;
  for (const Episode& e : data.demos) {
    for (const Sample& s : e.samples) {
      if (n++ == count) return out;
      for (float v : policy.Features(s.x, s.y)) out.push_back(v);
      for (float v : policy.Act(s.x, s.y)) out.push_back(v);
    }
  }
  return out;
}

/// Trains `train` on `data` once through, and once cancelled after 30 steps, checkpointed to
/// `path`, resumed and finished; true if both end in bitwise the same policy (every generator
/// stream a setting draws from must be in the checkpoint).
inline bool ResumedRunMatchesUninterrupted(const Dataset& data, const NetworkConfig& network,
                                           const TrainConfig& train, const std::string& path) {
  Trainer whole(data, network, train);
  whole.Train();
  std::atomic<bool> cancel{false};
  Trainer half(data, network, train);
  half.SetObserver([&](const StepMetrics& m) {
    if (m.step == 29) cancel = true;
  });
  if (!half.Train(&cancel).cancelled) return false;
  half.SaveCheckpoint(path);
  const std::unique_ptr<Trainer> resumed = Trainer::Resume(path, data);
  resumed->Train();
  return BitwiseEqual(Probe(resumed->policy(), data), Probe(whole.policy(), data));
}

}  // namespace recon::learn::testing
