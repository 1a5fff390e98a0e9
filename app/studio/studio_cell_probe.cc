// StudioCell's "Check what it looks at": the distractor probe and the features' read-out of the
// trained methods (cli::ProbeSession, as `recon eval --probe`), run as a job with its progress,
// cancellable, kept in the session for the Rollouts step and the report.

#include <string>

#include "app/cli/session_probe.h"
#include "app/studio/studio_cell.h"
#include "engine/core/error.h"

namespace recon::studio {

void StudioCell::Apply(const ui::RunProbe&) {
  RequireIdle("check what the policies look at");
  jobs_.Start(JobKind::kProbe, [this](JobThread& jobs) -> std::function<void()> {
    cli::SessionProbeOptions options;  // every trained method and object, 10 x 10, 60 scenes
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
      return [this, seconds] {
        Changed();
        status_ = "Checked what the policies look at in " + std::to_string(seconds).substr(0, 4) +
                  " s: see the heat maps under the rollouts.";
      };
    } catch (const probe::ProbeCancelled&) {
      return [this] { status_ = "Probe cancelled; the session keeps the probe it had."; };
    }
  });
}

void StudioCell::Apply(const ui::CancelProbe&) { jobs_.Cancel(); }

void StudioCell::Apply(const ui::ShowProbeObject& c) {
  probe_object_ = c.object;  // the session view checks it against what was probed
}

}  // namespace recon::studio
