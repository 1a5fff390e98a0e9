#include "engine/core/pauses.h"

namespace recon {

bool IsPause(const Episode& episode, size_t t, const std::vector<float>& motion) {
  if (t >= episode.samples.size()) return false;
  const std::vector<float>& u = episode.samples[t].u;
  // The first sample's discrete commands are compared with themselves: a take that begins with
  // the teacher looking begins with pauses.
  const std::vector<float>& before = episode.samples[t == 0 ? 0 : t - 1].u;
  if (before.size() != u.size()) return false;
  for (size_t i = 0; i < u.size(); ++i) {
    const bool is_motion = motion.empty() || (i < motion.size() && motion[i] != 0.0f);
    if (is_motion ? u[i] != 0.0f : u[i] != before[i]) return false;
  }
  return true;
}

Dataset WithoutPauses(const Dataset& dataset, const std::vector<float>& motion, int64_t* dropped,
                      const std::vector<bool>& of) {
  Dataset out;
  out.spec = dataset.spec;
  out.play = dataset.play;
  out.play_chunks = dataset.play_chunks;
  int64_t gone = 0;
  for (size_t d = 0; d < dataset.demos.size(); ++d) {
    const Episode& episode = dataset.demos[d];
    if (!of.empty() && (d >= of.size() || !of[d])) {
      out.demos.push_back(episode);
      continue;
    }
    Episode kept;
    for (size_t t = 0; t < episode.samples.size(); ++t) {
      if (!IsPause(episode, t, motion)) kept.samples.push_back(episode.samples[t]);
    }
    if (kept.samples.empty() && !episode.samples.empty())
      kept.samples.push_back(episode.samples[0]);
    gone += static_cast<int64_t>(episode.samples.size() - kept.samples.size());
    out.demos.push_back(std::move(kept));
  }
  if (dropped != nullptr) *dropped = gone;
  return out;
}

}  // namespace recon
