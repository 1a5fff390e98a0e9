#include "engine/learn/training_data.h"

#include <algorithm>

namespace recon::learn {

namespace {

template <typename Buffer>
void Append(Buffer& out, const std::vector<float>& values, float scale = 1.0f) {
  if (scale == 1.0f) {
    out.insert(out.end(), values.begin(), values.end());
  } else {
    for (float v : values) out.push_back(v * scale);
  }
}

}  // namespace

TrainingData TrainingData::From(const Dataset& dataset, float image_scale, int action_chunk) {
  TrainingData t;
  t.action_chunk = action_chunk;
  t.spec = dataset.spec;
  t.y_size = dataset.spec.YSize();
  t.num_demo = dataset.NumDemoSamples();
  t.num_play = static_cast<int64_t>(dataset.play.size());
  const float scale = dataset.spec.YIsImage() ? image_scale : 1.0f;
  t.demo_x.reserve(t.num_demo * t.spec.x_dim);
  t.demo_y.reserve(t.num_demo * t.y_size);
  t.demo_b.reserve(t.num_demo * t.spec.b_dim);
  t.demo_u.reserve(t.num_demo * t.spec.u_dim * action_chunk);
  t.demo_episode.reserve(t.num_demo);
  for (size_t e = 0; e < dataset.demos.size(); ++e) {
    const Episode& episode = dataset.demos[e];
    const size_t length = episode.samples.size();
    t.demo_episode.insert(t.demo_episode.end(), length, static_cast<int32_t>(e));
    for (size_t i = 0; i < length; ++i) {
      const Sample& s = episode.samples[i];
      Append(t.demo_x, s.x);
      Append(t.demo_y, s.y, scale);
      Append(t.demo_b, s.b);
      for (int k = 0; k < action_chunk; ++k) {
        Append(t.demo_u, episode.samples[std::min(i + k, length - 1)].u);
      }
    }
  }
  t.play_x.reserve(t.num_play * t.spec.x_dim);
  t.play_y.reserve(t.num_play * t.y_size);
  t.play_b.reserve(t.num_play * t.spec.b_dim);
  for (const PlaySample& p : dataset.play) {
    Append(t.play_x, p.x);
    Append(t.play_y, p.y, scale);
    Append(t.play_b, p.b);
  }
  t.fingerprint = Fingerprint(dataset);
  return t;
}

}  // namespace recon::learn
