// StudioCell's snapshots: what the screens show of the session, the cell and the jobs.

#include <algorithm>
#include <cmath>

#include "app/cli/session_training.h"
#include "app/studio/cell_view.h"
#include "app/studio/session_view.h"
#include "app/studio/studio_cell.h"
#include "engine/core/error.h"

namespace recon::studio {

void StudioCell::Publish(ui::StudioSnapshot& s) {
  if (!session_) {
    s = {};
    ShowWorkflow(teach::WorkflowFacts{}, s);  // the steps say they wait for a session
    s.picking_session = true;
    s.studio_cell = s.cell_kind = source_->Kind();
    s.recent_sessions = recent_.Openable();
    ShowConnected(s);
    ShowSafety(s);
    s.errors = errors_;
    s.status = status_;
    return;
  }
  if (dirty_) {
    RebuildSessionView();
    dirty_ = false;
  }
  s = session_view_;
  s.current_step = current_step_;
  if (world_) {
    s.play_scene_samples = world_->PlaySamplesPerScenario() * world_->DemosPerConfiguration();
  }
  s.picking_session = picking_session_;
  s.recent_sessions = recent_.Openable();
  RenderView(s);
  const JobState job = jobs_.Peek();
  s.calibration.running = job.running && job.kind == JobKind::kCalibration;
  s.calibration.points_collected = job.calibration_points;
  if (calibrating_) {
    s.calibration.running = true;
    s.calibration.guided = guided_calibration_;
    s.calibration.points_collected = guided_calibration_.points_taken;
    s.calibration.points_target = guided_calibration_.points_target;
  }
  s.recording = recorder_ && recorder_->recording();
  s.recording_samples = recorder_ ? recorder_->samples() : 0;
  s.recording_max_samples = world_->EpisodeLength();
  s.recording_step_s = world_->StepSeconds();
  s.pending_take = pending_take_;
  s.take_homing = s.recording && homing_take_;
  if (s.recording) {
    s.countdown_s = std::max(0.0, std::chrono::duration<double>(take_starts_ - Now()).count());
  }
  s.undo_delete = last_deleted_ ? last_deleted_->name : "";
  s.teleop = teleop_mode_;
  s.teleop_input = teleop_input_;
  source_->ShowDevices(s);
  source_->ShowArm(*world_, s);
  s.recording_play = play_ && play_->recording();
  s.play_recorded = play_done_ + (play_ ? play_->samples() : 0);
  s.play_target = play_target_;
  s.play_image = play_image_;
  s.play_image_frame = play_image_frame_;
  s.play_reading = play_reading_;
  ShowDeviceHealth(s);
  ShowConnected(s);
  ShowSafety(s);
  // A training's live views stay until its result is taken (then the session view shows the
  // saved models), so the screen never flashes the models from before.
  const bool training_job = job.kind == JobKind::kTraining &&
                            (job.running || job.finish != nullptr || !job.error.empty());
  if (training_job) s.training = job.training;
  s.training_running = job.running && job.kind == JobKind::kTraining;
  s.training_cancelling = s.training_running && jobs_.cancel_flag()->load();
  s.rollouts_running = job.running && job.kind == JobKind::kRollouts;
  s.rollouts_cancelling = s.rollouts_running && jobs_.cancel_flag()->load();
  if (s.rollouts_running) {
    s.rollout_steps_done = job.rollout_steps_done;
    s.rollout_steps_total = job.rollout_steps_total;
  }
  s.probe.running = job.running && job.kind == JobKind::kProbe;
  s.probe.cancelling = s.probe.running && jobs_.cancel_flag()->load();
  if (s.probe.running) {
    s.probe.phase = job.probe_phase;
    s.probe.done = job.probe_done;
    s.probe.total = job.probe_total;
  }
  s.busy_with = s.recording           ? "the recording"
                : s.recording_play    ? "the play data recording"
                : calibrating_        ? "the calibration"
                : trial_              ? "the trials"
                : jobs_.RunningKind() ? std::string("the ") + JobKindName(*jobs_.RunningKind())
                                      : "";
  s.rollout_tests = options_.rollout_tests;
  if (world_) {
    const int steps = cli::SessionRolloutSteps(*session_, *world_, &s.rollout_limit_note);
    s.rollout_limit_s = steps * world_->StepSeconds();
    for (const int64_t samples : cli::KeptDemoLengths(*session_)) {
      s.longest_take_s = std::max(s.longest_take_s, samples * world_->StepSeconds());
    }
  }
  ShowPlayback(s);
  ShowTrial(s);
  s.trial_playback = trial_playback_;
  s.episode_playback = episode_playback_;
  s.saliency = saliency_;
  if (!report_path_.empty()) s.report_path = report_path_;  // else the session view's
  s.errors = errors_;
  s.status = job.running ? std::string("Running ") + JobKindName(*job.kind) + "..." : status_;
}

void StudioCell::RebuildSessionView() {
  SessionViewInputs inputs;
  inputs.recording_demos = recorder_ && recorder_->recording();
  inputs.training = jobs_.RunningKind() == JobKind::kTraining;
  inputs.calibration_points = options_.calibration_points;
  inputs.gamepad = gamepad_.View();
  inputs.studio_cell = source_->Kind();
  inputs.probe_object = probe_object_;
  inputs.suggested_demos = world_ ? world_->SuggestedDemos() : 1;
  session_view_ = BuildSessionView(*session_, inputs);
}

void StudioCell::RenderView(ui::StudioSnapshot& s) {
  // The simulated camera is rendered only for the screens that show it (or while a take runs),
  // so training and rollouts get the CPU it would take.
  bool wanted = recorder_ && recorder_->recording();
  switch (current_step_) {
    case teach::Step::kCell:
    case teach::Step::kBeacons:
    case teach::Step::kRecord:
    case teach::Step::kPlay:
      wanted = true;
      break;
    default:
      break;
  }
  const ViewSize view{options_.view_width, options_.view_height};
  if (source_->ShowLive(*world_, *session_, last_reading_, wanted, view, s)) {
    camera_health_.Add(Seconds(Now()));
  }
  // The teacher's 3-D view is the Record screen's only (shadows make it the costliest frame).
  if (current_step_ == teach::Step::kRecord) {
    source_->ShowTeacherView(*world_, teacher_view_,
                             {options_.teacher_view_width, options_.teacher_view_height}, s);
  }
}

void StudioCell::ShowDeviceHealth(ui::StudioSnapshot& s) const {
  const double now = Seconds(Now());
  const teach::StreamStats camera = camera_health_.Stats(now);
  const teach::StreamStats beacon = beacon_health_.Stats(now);
  const teach::StreamStats arm = arm_health_.Stats(now);
  for (ui::DeviceView& d : s.devices) {
    if (d.role == "camera") d.rate_hz = camera.rate_hz;
    if (d.role == "beacons") d.rate_hz = beacon.rate_hz;
    if (d.role == "arm") d.rate_hz = arm.rate_hz;  // commanded while recording, else idle
  }
  for (ui::BeaconView& b : s.beacons) {
    b.rate_hz = beacon.rate_hz;
    b.dropout_fraction = beacon.dropout_fraction;
    // Per axis, as a beacon's noise is specified (StreamStats::noise sums the axes' variances).
    b.noise_m =
        beacon.noise / std::sqrt(static_cast<double>(std::max<size_t>(1, b.reading.size())));
  }
}

void StudioCell::ShowConnected(ui::StudioSnapshot& s) const {
  uint64_t scans = 0;
  s.connected = scanner_.Latest(&scans);
  s.connected_scanned = scans > 0;
  s.connected_where = scanner_.Where();
}

void StudioCell::ShowSafety(ui::StudioSnapshot& s) const {
  s.safety.estop = estop_;
  s.safety.estop_reason = estop_reason_;
  const safety::GuardedArm* arm = source_->GuardedArmOf(world_.get());
  if (arm == nullptr) return;
  const safety::SafetyStats stats = arm->stats();
  s.safety.limits = safety::DescribeLimits(arm->envelope().limits());
  s.safety.commands = stats.commands;
  s.safety.changed = stats.changed;
  // The arm's own latch is what holds the robot: show it, not what the studio asked for.
  s.safety.estop = arm->emergency_stopped();
  s.safety.estop_reason = arm->emergency_stop_reason();
}

void StudioCell::ShowPlaySample() {
  const PlaySample* sample = play_->last();
  if (sample == nullptr) return;
  play_image_ = ImageFromObservation(sample->y, session_->manifest().image_size);
  ++play_image_frame_;
  play_reading_ = sample->b;
  last_reading_ = sample->b;
  beacon_health_.Add(Seconds(Now()), last_reading_);
}

void StudioCell::ShowPlayback(ui::StudioSnapshot& s) {
  if (current_step_ != teach::Step::kRollouts || !playback_) return;
  // Drawn only while the Rollouts screen shows: two renders per step shown.
  try {
    playback_->Fill(s.rollouts, *renderer_, options_.view_width, options_.view_height);
    s.rollouts_playing = playback_->playing();
  } catch (const UserError& e) {
    // A scene's data is damaged: say so once and stop the playback, not the studio.
    AddError(std::string("cannot play the rollouts back: ") + e.what());
    playback_ = std::make_unique<RolloutPlayback>(session_->manifest(), session_->dir());
  }
}

}  // namespace recon::studio
