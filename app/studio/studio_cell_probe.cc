// StudioCell's "Check what it looks at": the distractor probe and the features' read-out of the
// trained methods (cli::ProbeSession, as `recon eval --probe`), run as a job with its progress,
// cancellable, kept in the session for the Rollouts step and the report; and the saliency laid
// over the frames played back (rollouts, and the trials' recorded frames).

#include <cstdio>
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
    cli::SessionProbeOptions options;  // every trained method and object, 10 x 10, 60 scenes
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
}

void StudioCell::DrawTrialFrame() {
  const size_t frame = static_cast<size_t>(trial_playback_.frame);
  RgbImage image = ImageFromObservation(trial_frames_.y[frame], trial_frames_.image_size);
  if (saliency_ != ui::SaliencyMode::kOff) {
    if (!trial_policy_ || trial_policy_method_ != trial_playback_.method) {
      trial_policy_ = learn::LoadPolicy(session_->CheckpointPath(trial_playback_.method));
      trial_policy_method_ = trial_playback_.method;
    }
    const std::vector<float>& x = trial_frames_.x[frame];
    const std::vector<float>& y = trial_frames_.y[frame];
    const probe::SaliencyMap map = saliency_ == ui::SaliencyMode::kGradient
                                       ? probe::GradientSaliency(*trial_policy_, x, y)
                                       : probe::OcclusionSaliency(*trial_policy_, x, y);
    image = probe::OverlaySaliency(image, map);
  }
  trial_playback_.image = std::move(image);
  ++trial_playback_.image_frame;
}

void StudioCell::Apply(const ui::ShowProbeObject& c) {
  probe_object_ = c.object;  // the session view checks it against what was probed
}

}  // namespace recon::studio
