// StudioCell's "Check what it looks at": the distractor probe and the features' read-out of the
// trained methods (cli::ProbeSession, as `recon eval --probe`), run as a job with its progress,
// cancellable, kept in the session for the Rollouts step and the report; and the saliency laid
// over the frames played back (rollouts, and the trials' recorded frames).

#include <cstdio>
#include <filesystem>
#include <string>

#include "app/cli/session_probe.h"
#include "app/studio/cell_view.h"
#include "app/studio/studio_cell.h"
#include "engine/core/error.h"
#include "engine/learn/learner.h"
#include "engine/probe/saliency.h"

namespace recon::studio {

void StudioCell::Apply(const ui::RunProbe& c) {
  RequireIdle("check what the policies look at");
  jobs_.Start(JobKind::kProbe, [this, c](JobThread& jobs) -> std::function<void()> {
    cli::SessionProbeOptions options;  // every trained method and object, 60 read-out scenes
    options.grid.nx = options.grid.ny = options_.probe_grid;
    options.outcome = c.outcome;
    try {
      const store::ProbeSummary summary = cli::ProbeSession(
          *session_, options,
          [&jobs](const std::string& what, int done, int total) {
            jobs.Update([&](JobState& state) {
              state.probe_phase = what;
              state.probe_done = done;
              state.probe_total = total;
            });
          },
          jobs.cancel_flag());
      const double seconds = summary.seconds;
      const bool moved = summary.readout_scenes > 0;
      return [this, seconds, moved] {
        Changed();
        char took[32];
        std::snprintf(took, sizeof(took), "%.1f", seconds);
        status_ = moved ? std::string("Checked what the policies look at in ") + took +
                              " s: see the heat maps under the rollouts."
                        : std::string("Read out what the features encode in ") + took +
                              " s: see the table under the trials.";
      };
    } catch (const probe::ProbeCancelled&) {
      return [this] { status_ = "Probe cancelled; the session keeps the probe it had."; };
    }
  });
}

void StudioCell::Apply(const ui::CancelProbe&) { jobs_.Cancel(); }

void StudioCell::Apply(const ui::SetSaliency& c) {
  saliency_ = c.mode;
  if (playback_) playback_->SetSaliency(c.mode);
  if (trial_playback_.number > 0 && trial_playback_.frames > 0) DrawTrialFrame();
  if (!episode_playback_.episode.empty() && episode_playback_.frames > 0) DrawEpisodeFrame();
}

RgbImage StudioCell::SaliencyFrame(const store::TrialFrames& frames, size_t frame,
                                   const std::string& method) {
  RgbImage image = ImageFromObservation(frames.y[frame], frames.image_size);
  if (saliency_ == ui::SaliencyMode::kOff || method.empty()) return image;
  const std::string checkpoint = session_->CheckpointPath(method);
  const std::filesystem::file_time_type written = std::filesystem::last_write_time(checkpoint);
  auto model = saliency_models_.find(method);
  if (model == saliency_models_.end() || model->second.written != written) {
    model = saliency_models_
                .insert_or_assign(method, SaliencyModel{written, learn::LoadPolicy(checkpoint)})
                .first;
  }
  const learn::Policy& policy = model->second.policy;
  const std::vector<float>& x = frames.x[frame];
  const std::vector<float>& y = frames.y[frame];
  const probe::SaliencyMap map = saliency_ == ui::SaliencyMode::kGradient
                                     ? probe::GradientSaliency(policy, x, y)
                                     : probe::OcclusionSaliency(policy, x, y);
  return probe::OverlaySaliency(image, map);
}

void StudioCell::DrawTrialFrame() {
  trial_playback_.image = SaliencyFrame(trial_frames_, static_cast<size_t>(trial_playback_.frame),
                                        trial_playback_.method);
  ++trial_playback_.image_frame;
}

void StudioCell::Apply(const ui::ShowProbeObject& c) {
  probe_object_ = c.object;  // the session view checks it against what was probed
}

}  // namespace recon::studio
