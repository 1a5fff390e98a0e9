#pragma once

#include <vector>

#include "engine/store/session.h"
#include "engine/teach/workflow.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// What the session's side of the snapshot needs beyond the session's files: what runs now and
/// what is plugged in.
struct SessionViewInputs {
  bool recording_demos = false;
  bool training = false;
  int calibration_points = 12;
  ui::DeviceView gamepad;  ///< GamepadSource::View()
  /// The cell the studio drives (CellSource::Kind()); a session taught in another one records
  /// nothing here (WorkflowFacts::taught_elsewhere).
  std::string studio_cell = "simulated";
  std::string probe_object;  ///< whose heat maps the probe panel shows (ShowProbeObject)
  /// The demonstrations the world's protocol asks for before training (World::SuggestedDemos).
  int suggested_demos = 1;
};

/// The workflow of `facts` into `s`: each step's state, which steps can open, the next one.
/// The next step stays Record until `suggested_demos` demonstrations are kept (Train is open
/// from the first, as the workflow says, but the docs' advice is the one marked next).
void ShowWorkflow(const teach::WorkflowFacts& facts, ui::StudioSnapshot& s,
                  int suggested_demos = 1);

/// The session's side of the snapshot: devices and teleops, workflow, calibration, episodes,
/// play samples, teaching time and rollouts. Reads the calibration and the rollout files, so the
/// studio rebuilds it when something changed, not at the camera's 30 Hz.
ui::StudioSnapshot BuildSessionView(const store::Session& session, const SessionViewInputs& inputs);

}  // namespace recon::studio
