#include "app/studio/session_view.h"

#include <filesystem>
#include <optional>
#include <string>

#include "app/cli/result_staleness.h"
#include "app/cli/session_summary.h"
#include "app/cli/session_training.h"
#include "app/studio/probe_view.h"
#include "app/studio/training_mark.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/store/rollout_summary.h"
#include "engine/store/training_record.h"
#include "engine/teach/teacher_mix.h"
#include "engine/worlds/outcome_words.h"

namespace recon::studio {

namespace fs = std::filesystem;

namespace {

/// Why a session taught in the `cell` cell records nothing in the studio's other cell (short:
/// the step list shows it under four steps; the Cell screen and refusals say more).
std::string TaughtElsewhere(const std::string& cell) {
  return "Taught in the " + cell + " cell, recorded there";
}

teach::WorkflowFacts Facts(const store::Session& session, const SessionViewInputs& inputs,
                           const std::optional<calib::CalibrationReport>& calibration,
                           const cli::SessionResults& results, bool report_written) {
  const store::SessionManifest& m = session.manifest();
  teach::WorkflowFacts f;
  f.session_open = true;
  f.cell_connected = true;  // simulated devices are always there
  f.beacons_required = static_cast<int>(m.beacons.size());
  f.beacons_assigned = static_cast<int>(m.beacon_assignments.size());
  for (const BeaconSpec& b : m.beacons) {
    if (!m.beacon_assignments.count(b.name)) f.unmarked_objects.push_back(b.object);
  }
  if (calibration) {
    f.calibration_present = true;
    f.calibration_passed = calibration->passed;
    f.calibration_rmse_m = calibration->rmse_m;
  }
  for (const store::EpisodeEntry& e : session.demos()) {
    if (e.flags.bad || !e.problem.empty()) continue;
    ++f.demos;
    f.demo_seconds += e.meta.teaching_seconds;
  }
  f.play_samples = static_cast<int>(session.PlaySamples());
  f.recording_demos = inputs.recording_demos;
  f.training = inputs.training;
  for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
    if (fs::exists(session.CheckpointPath(method))) f.trained_methods.push_back(method);
    // Rollouts of a model retrained since (or trained on other data) are not this model's.
    const auto rollouts = results.rollouts.find(method);
    if (rollouts == results.rollouts.end()) continue;
    (rollouts->second.out_of_date.empty() ? f.evaluated_methods : f.outdated_evaluations)
        .push_back(method);
  }
  f.report_written = report_written;
  if (m.cell != inputs.studio_cell) f.taught_elsewhere = TaughtElsewhere(m.cell);
  return f;
}

ui::CalibrationView CalibrationView(const std::optional<calib::CalibrationReport>& calibration) {
  ui::CalibrationView view;
  if (!calibration) return view;
  view.present = true;
  view.passed = calibration->passed;
  view.rmse_m = calibration->rmse_m;
  view.p95_m = calibration->p95_m;
  view.threshold_m = calibration->options.pass_rmse_m;
  view.residual_m = calibration->residual_norm_m;
  for (bool outlier : calibration->outlier) view.inlier.push_back(!outlier);
  return view;
}

/// A model saved in the session as the Train screen shows it: finished, with its loss curves.
ui::TrainingView SavedTrainingView(const cli::CheckedResult<store::TrainingRecord>& saved) {
  const store::TrainingRecord& t = saved.record;
  ui::TrainingView view;
  view.method = t.method;
  view.label = t.label;
  view.done = true;
  view.step = view.steps = t.steps;
  view.seconds = t.seconds;
  view.loss = t.loss;
  const store::TrainingHistory& h = t.history;
  for (size_t i = 0; i < h.step.size(); ++i) {
    view.loss_step.push_back(static_cast<float>(h.step[i]));
    if (i < h.action_loss.size()) view.action_loss.push_back(static_cast<float>(h.action_loss[i]));
    if (t.method == teach::kReconMethod && i < h.beacon_loss.size()) {
      view.beacon_loss.push_back(static_cast<float>(h.beacon_loss[i]));
    }
    if (i < h.total_loss.size()) view.total_loss.push_back(static_cast<float>(h.total_loss[i]));
  }
  view.out_of_date = saved.out_of_date;
  return view;
}

}  // namespace

void ShowWorkflow(const teach::WorkflowFacts& facts, ui::StudioSnapshot& s, int suggested_demos) {
  s.steps = teach::EvaluateWorkflow(facts);
  for (int i = 0; i < teach::kNumSteps; ++i) {
    s.can_open[i] = teach::CanOpen(facts, teach::kAllSteps[i]);
  }
  s.next_step = teach::NextStep(facts);
  const auto index = [](teach::Step step) { return static_cast<int>(step); };
  const teach::StepStatus& record = s.steps[index(teach::Step::kRecord)];
  const bool record_open = record.state != teach::StepState::kBlocked;
  const bool busy = s.steps[index(s.next_step)].state == teach::StepState::kBusy;
  if (record_open && !busy && facts.demos < suggested_demos &&
      index(s.next_step) > index(teach::Step::kRecord)) {
    s.next_step = teach::Step::kRecord;
    s.steps[index(teach::Step::kRecord)].summary +=
        "; " + std::to_string(suggested_demos) + " suggested before training";
  }
}

ui::StudioSnapshot BuildSessionView(const store::Session& session,
                                    const SessionViewInputs& inputs) {
  const store::SessionManifest& m = session.manifest();
  ui::StudioSnapshot s;
  s.session_open = true;
  s.session_dir = session.dir();
  // While a training runs its note is there and says nothing: only one left behind was cut short.
  if (!inputs.training) s.training_cut_short = TrainingCutShort(session.dir());
  s.world = m.world;
  s.cell_kind = m.cell;
  s.studio_cell = inputs.studio_cell;
  for (const store::DeviceEntry& d : m.devices) {
    if (d.role == "teleop") continue;  // the teleops are listed below, from what is plugged in
    s.devices.push_back({d.role, d.kind, d.detail, true, 0.0, ""});
  }
  s.devices.push_back({"teleop", "keyboard",
                       "arrows move the arm, Page Up/Down raise and "
                       "lower it, Space opens and closes the gripper",
                       true, 0.0, ""});
  s.devices.push_back(inputs.gamepad);
  s.teleop_choices = {
      {ui::TeleopMode::kScripted, m.cell != "real", "a real cell has no scripted teacher"},
      {ui::TeleopMode::kKeyboard, true, ""},
      {ui::TeleopMode::kGamepad, inputs.gamepad.connected, "no gamepad connected"}};
  std::optional<calib::CalibrationReport> calibration;
  if (!m.calibration_file.empty()) {
    calibration = calib::LoadCalibration((fs::path(session.dir()) / m.calibration_file).string());
  }
  // Every training record and rollout summary is read, and checked against its checkpoint, once.
  const cli::SessionResults results = cli::ReadSessionResults(session);
  const std::string report = session.ReportPath();
  const bool report_written = fs::exists(report);
  ShowWorkflow(Facts(session, inputs, calibration, results, report_written), s,
               inputs.suggested_demos);
  s.calibration = CalibrationView(calibration);
  s.calibration.points_target = inputs.calibration_points;
  std::vector<std::string> sources;  // of the demonstrations training will use
  for (const store::EpisodeEntry& e : session.demos()) {
    s.episodes.push_back({e.name, static_cast<int>(e.meta.num_samples), e.meta.teaching_seconds,
                          e.meta.succeeded, e.flags.bad, e.flags.split, e.problem});
    if (!e.flags.bad && e.problem.empty()) sources.push_back(e.meta.source);
  }
  s.teacher_mix_warning = teach::TeacherMixWarning(sources);
  s.slow_takes_warning = cli::SlowTakesWarningOf(session);
  s.play_samples = static_cast<int>(session.PlaySamples());
  // A report written before (by the studio or `recon report`) can be opened too.
  if (report_written) s.report_path = report;
  const nlohmann::json ledger = cli::TeachingLedgerJson(session);
  s.teacher_seconds = ledger["teacher_total_s"].get<double>();
  s.teacher_discarded_seconds = ledger["discarded_s"].get<double>();
  s.teacher_discarded_takes = ledger["discarded_takes"].get<int>();
  s.teacher_countdown_seconds = ledger["countdowns_s"].get<double>();
  s.teacher_demo_seconds = ledger["demonstrations_s"].get<double>();
  s.teacher_play_seconds = ledger["play_s"].get<double>();
  s.teacher_placement_seconds = ledger["beacon_placements_s"].get<double>();
  for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
    const auto trained = results.training.find(method);
    if (trained == results.training.end() || !fs::exists(session.CheckpointPath(method))) {
      continue;
    }
    s.training.push_back(SavedTrainingView(trained->second));
  }
  for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
    const auto rollouts = results.rollouts.find(method);
    if (rollouts == results.rollouts.end()) continue;
    const store::RolloutSummary* r = &rollouts->second.record;
    ui::RolloutView view;
    view.method = method;
    view.label = r->label;
    view.metric_name = r->metric_name;
    view.metric_mean = r->metric_mean;
    view.metric_sem = r->metric_sem;
    view.has_success = r->has_success;
    view.success_rate = r->success_rate;
    view.tests = r->tests;
    for (const store::ScenarioResult& scene : r->per_scenario) {
      view.scene_failures.push_back(worlds::DescribeFailure(scene.details, scene.succeeded));
    }
    view.out_of_date = rollouts->second.out_of_date;
    s.rollouts.push_back(view);
  }
  for (const auto& [method, checked] : results.trials) {
    const store::RealTrialLog& log = checked.record;
    ui::RealTrialsView view;
    view.method = method;
    view.label = log.label;
    view.successes = log.successes();
    for (const store::RealTrial& t : log.trials) {
      view.trials.push_back({t.number, t.succeeded, t.stopped, t.reason, t.frames.has_value()});
    }
    view.out_of_date = checked.out_of_date;
    s.real_trials.push_back(view);
  }
  try {
    s.probe = BuildProbeView(session, inputs.probe_object);
  } catch (const UserError& e) {
    // A damaged probe.json is said where the probe is shown; probing again replaces it.
    s.probe.out_of_date = std::string("cannot read the probe: ") + e.what();
  }
  return s;
}

}  // namespace recon::studio
