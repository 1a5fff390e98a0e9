// StudioCell's playback of a recorded demonstration on the Record screen: what the camera saw
// while the teacher showed the task, frame by frame, with the saliency of a trained method laid
// over it, so a teacher sees what a policy would act on in their own demonstrations.

#include <algorithm>
#include <filesystem>
#include <string>

#include "app/cli/session_probe.h"
#include "app/studio/studio_cell.h"
#include "engine/core/error.h"

namespace recon::studio {

void StudioCell::Apply(const ui::ShowEpisodeFrame& c) {
  if (c.episode.empty()) {  // closed
    episode_playback_ = {};
    episode_frames_ = {};
    return;
  }
  if (!session_->manifest().spec.YIsImage()) {
    throw UserError("the " + session_->manifest().world +
                    " world records no camera image to play back");
  }
  if (c.episode != episode_playback_.episode) {
    const store::EpisodeEntry& entry = session_->Find(c.episode);  // UserError naming it
    if (entry.meta.kind != "demo") {
      throw UserError(c.episode + " is play data, not a demonstration");
    }
    const store::DemoRecord demo = session_->ReadDemo(c.episode);
    store::TrialFrames frames;
    frames.image_size = session_->manifest().image_size;
    for (const Sample& sample : demo.episode.samples) {
      frames.x.push_back(sample.x);
      frames.y.push_back(sample.y);
    }
    episode_frames_ = std::move(frames);
    episode_playback_.episode = c.episode;
  }
  // The methods a saliency can be drawn for: the trained ones.
  episode_playback_.methods.clear();
  for (const char* method : {"baseline", "recon"}) {
    if (std::filesystem::exists(session_->CheckpointPath(method))) {
      episode_playback_.methods.emplace_back(method, cli::MethodLabel(*session_, method));
    }
  }
  const auto trained = [&](const std::string& method) {
    return std::any_of(episode_playback_.methods.begin(), episode_playback_.methods.end(),
                       [&](const auto& m) { return m.first == method; });
  };
  if (!c.method.empty() && !trained(c.method)) {
    throw UserError(c.method + " is not trained: there is no saliency of it to show");
  }
  episode_playback_.method = !c.method.empty()                   ? c.method
                             : trained(episode_playback_.method) ? episode_playback_.method
                             : !episode_playback_.methods.empty()
                                 ? episode_playback_.methods[0].first
                                 : "";
  episode_playback_.frames = static_cast<int>(episode_frames_.y.size());
  episode_playback_.frame = std::clamp(c.frame, 0, std::max(0, episode_playback_.frames - 1));
  if (episode_playback_.frames > 0) DrawEpisodeFrame();
}

void StudioCell::DrawEpisodeFrame() {
  episode_playback_.image = SaliencyFrame(
      episode_frames_, static_cast<size_t>(episode_playback_.frame), episode_playback_.method);
  ++episode_playback_.image_frame;
}

}  // namespace recon::studio
