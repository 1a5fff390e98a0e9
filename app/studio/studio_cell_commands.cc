// StudioCell's commands: what each of the UI's commands does to the session and the cell.

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>
#include <thread>

#include "app/cli/session_report_builder.h"
#include "app/cli/session_training.h"
#include "app/studio/studio_cell.h"
#include "app/studio/studio_jobs.h"
#include "app/studio/training_mark.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"

namespace recon::studio {

namespace fs = std::filesystem;

void StudioCell::Apply(const ui::OpenStep& c) { current_step_ = c.step; }

void StudioCell::Apply(const ui::AssignBeacon& c) {
  RequireIdle("assign a beacon");
  RequireTaughtHere("assign a beacon");
  // A label that the readings would contradict is refused: a simulated beacon that cannot move
  // would go on reporting the plate while the session said it marks the bowl.
  if (const std::optional<std::string> fixed = source_->FixedBeaconObject();
      fixed && *fixed != c.object) {
    throw UserError("beacon " + c.beacon + " stays beside the " + *fixed +
                    " in the simulated cell (the paper's placement), so it cannot mark the " +
                    c.object + "; on a real cell a beacon marks whatever you stick it on");
  }
  session_->AssignBeacon(c.beacon, c.object);
  status_ = "Beacon " + c.beacon + " marks the " + c.object + ".";
}

void StudioCell::Apply(const ui::StartCalibration&) {
  RequireIdle("calibrate");
  RequireTaughtHere("calibrate");
  const int points = options_.calibration_points;
  if (source_->GuidesCalibration()) {
    // The teacher moves the beacon place by place; the cell loop follows (StepCalibration).
    source_->StartGuidedCalibration(points);
    guided_calibration_ = ui::GuidedCalibrationView{};
    calibrating_ = true;
    status_ = "Calibrating: move the beacon to each place the Calibrate step asks for.";
    return;
  }
  const uint64_t seed = session_->manifest().seed;
  const std::string dir = session_->dir();
  jobs_.Start(JobKind::kCalibration,
              [this, seed, points, dir](JobThread& jobs) -> std::function<void()> {
                const std::string path = (fs::path(dir) / "calibration.new.json").string();
                CalibrateCell(jobs, seed, points, path);
                return [this, path] { AttachCalibration(path); };
              });
}

void StudioCell::Apply(const ui::CancelCalibration&) {
  if (calibrating_) {
    source_->StopGuidedCalibration();
    calibrating_ = false;
    status_ = "Calibration cancelled: the session keeps the calibration it had.";
    return;
  }
  jobs_.Cancel();
}

void StudioCell::AttachCalibration(const std::string& path) {
  session_->AttachCalibration(path);
  fs::remove(path);
  if (source_->GuidesCalibration()) {
    // A real cell's world reads the beacon through the calibration: make it again with it.
    world_ = source_->MakeSessionWorld(*session_);
    HoldEmergencyStop();
  }
  const calib::CalibrationReport report = calib::LoadCalibration(
      (fs::path(session_->dir()) / session_->manifest().calibration_file).string());
  status_ = std::string("Calibrated: ") + (report.passed ? "PASS" : "FAIL") + ".";
}

void StudioCell::StepCalibration() {
  std::optional<calib::CalibrationReport> report;
  try {
    report = source_->StepGuidedCalibration(guided_calibration_);
  } catch (const UserError& e) {
    source_->StopGuidedCalibration();
    calibrating_ = false;
    Changed();
    AddError(std::string("the calibration stopped: ") + e.what());
    return;
  }
  if (!report) return;
  calibrating_ = false;
  Changed();
  const std::string path = (fs::path(session_->dir()) / "calibration.new.json").string();
  calib::SaveCalibration(*report, path);
  AttachCalibration(path);
}

void StudioCell::Apply(const ui::StartRecording&) {
  RequireIdle("record");
  RequireTaughtHere("record");
  RequireNoEmergencyStop("record");
  const int number = session_->NextDemoNumber();
  StartDemo(number, store::Session::ScenarioSeed(session_->manifest().seed, number, false));
  status_ = teleop_mode_ == ui::TeleopMode::kScripted
                ? "Recording a demonstration (the scripted teacher)."
                : "Recording a demonstration: drive the arm, Stop and keep when done.";
}

void StudioCell::Apply(const ui::StopRecording&) {
  // Stop and keep, or Keep for a take set aside unfinished.
  if (TakeWaiting()) throw UserError("the take has not started yet: wait for it, or discard it");
  if (recorder_ && (recorder_->recording() || !pending_take_.empty())) Commit();
}

void StudioCell::Apply(const ui::DiscardRecording&) {
  // A discarded take still cost the teacher its time: the ledger keeps it.
  if (recorder_ && recorder_->samples() > 0 && session_) {
    session_->AddUnkeptTime(1, recorder_->samples() * world_->StepSeconds(), 0.0);
  }
  homing_take_ = false;
  recorder_.reset();
  replace_.reset();
  pending_take_.clear();
  // The next take starts from its own scene, the arm at home and the gripper open: what the
  // screen shows (and the grip's readout) must not stay where the discarded take left it.
  if (world_) ResetToNextScene();
  status_ = "Recording discarded.";
}

void StudioCell::Apply(const ui::DeleteEpisode& c) {
  RequireIdle("delete an episode");
  const store::EpisodeFlags flags = session_->Find(c.name).flags;
  last_deleted_ = Deleted{c.name, session_->DeleteEpisode(c.name), flags};
  if (episode_playback_.episode == c.name) Apply(ui::ShowEpisodeFrame{});  // nothing to show
  // The next take's number, and so its scene, may have changed: show the one it will use.
  ResetToNextScene();
  status_ = "Moved " + c.name + " to the session's trash (Undo brings it back).";
}

void StudioCell::Apply(const ui::UndoDelete&) {
  RequireIdle("undo a delete");
  if (!last_deleted_) throw UserError("nothing deleted to bring back");
  const Deleted deleted = *last_deleted_;
  session_->RestoreEpisode(deleted.trash_path, deleted.name, deleted.flags);
  last_deleted_.reset();
  ResetToNextScene();
  status_ = "Brought " + deleted.name + " back from the trash.";
}

void StudioCell::Apply(const ui::ReRecordEpisode& c) {
  RequireIdle("re-record");
  RequireTaughtHere("re-record");
  RequireNoEmergencyStop("re-record");
  const store::EpisodeEntry& e = session_->Find(c.name);
  StartDemo(e.number, e.meta.seed);
  replace_ = c.name;
  if (episode_playback_.episode == c.name) Apply(ui::ShowEpisodeFrame{});  // about to change
  status_ = "Re-recording " + c.name + ".";
}

void StudioCell::Apply(const ui::MarkEpisodeBad& c) {
  RequireIdle("mark an episode");
  session_->MarkBad(c.name, c.bad);
}

void StudioCell::Apply(const ui::RecordPlay& c) {
  RequireIdle("record play data");
  RequireTaughtHere("record play data");
  RequireNoEmergencyStop("record play data");
  if (c.samples < 1) throw UserError("ask for at least one play sample");
  play_target_ = c.samples;
  play_done_ = 0;
  StartPlayChunk();
  status_ = "Recording " + std::to_string(c.samples) + " play samples.";
}

void StudioCell::Apply(const ui::StopPlay&) {
  if (!play_ || !play_->recording()) return;
  // What was recorded is good data: keep it, and ask for no more.
  play_target_ = play_done_ + play_->samples();
  if (play_->samples() > 0) {
    CommitPlayChunk();
  } else {
    play_.reset();
  }
  status_ = "Stopped play recording after " + std::to_string(play_done_) + " samples.";
}

void StudioCell::Apply(const ui::SetTeleopMode& c) {
  if (recorder_ && recorder_->recording()) {
    throw UserError("finish or discard the recording before changing the teleop");
  }
  if (c.mode == ui::TeleopMode::kGamepad && !gamepad_.connected()) {
    throw UserError("no gamepad connected (looked for " + gamepad_.Places() + ")");
  }
  if (c.mode == ui::TeleopMode::kScripted && !source_->HasScriptedTeacher()) {
    throw UserError("a real cell has no scripted teacher: teach with the keyboard or a gamepad");
  }
  teleop_mode_ = c.mode;
  if (session_ && session_->manifest().cell == source_->Kind()) {
    session_->RememberTeleop(c.mode == ui::TeleopMode::kScripted   ? "scripted"
                             : c.mode == ui::TeleopMode::kKeyboard ? "keyboard"
                                                                   : "gamepad");
  }
}

void StudioCell::Apply(const ui::TeleopInput& c) {
  teleop_input_ = c;
  if (teleop_mode_ == ui::TeleopMode::kKeyboard) {
    // Keys are shaped period by period (ShapeKeyboardTeleop): a tap between two ticks still
    // moves a step.
    const double now = Seconds(Now());
    key_ramp_.Set(0, c.screen_right, now);
    key_ramp_.Set(1, c.screen_up, now);
    key_ramp_.Set(2, c.raise, now);
    key_ramp_.Set(3, c.turn, now);
    return;
  }
  const ViewSize view{options_.view_width, options_.view_height};
  teleop_command_.velocity_m_s =
      source_->TeleopVelocity(*world_, c, view, teacher_view_, kTeleopSpeed_m_s);
  teleop_command_.wrist_turn_rad_s =
      std::clamp(static_cast<double>(c.turn), -1.0, 1.0) * teach::kWristTurnSpeed_rad_s;
}

void StudioCell::Apply(const ui::ToggleGripper&) {
  // Only a person's take has a gripper to toggle; between takes the key does nothing, as the
  // arrows do.
  if (!(recorder_ && recorder_->recording()) || teleop_mode_ == ui::TeleopMode::kScripted) return;
  teleop_command_.close_gripper = !teleop_command_.close_gripper;
}

void StudioCell::Apply(const ui::SetTeacherView& c) {
  worlds::OrbitCamera view = teacher_view_;
  view.azimuth_deg = c.azimuth_deg;
  view.elevation_deg = c.elevation_deg;
  view.distance_m = c.distance_m;
  teacher_view_ = view.Clamped();
  // Keys held while the view turns now mean the new directions.
  if (world_) Apply(teleop_input_);
}

void StudioCell::Apply(const ui::ShowSessionPicker& c) { picking_session_ = c.show && !Busy(); }

void StudioCell::Apply(const ui::OpenSession& c) {
  RequireIdle("switch sessions");
  if (c.dir.empty()) throw UserError("type the session's folder first");
  OpenSessionAt(c.dir);
}

void StudioCell::Apply(const ui::PlayRollouts& c) { playback_->SetPlaying(c.playing, Now()); }

void StudioCell::Apply(const ui::StartTraining& c) {
  RequireIdle("train");
  cli::SessionTrainingOptions training;
  // --train-steps caps what the screen asks for; 0 leaves both to the world's recipe.
  training.steps = options_.train_steps;
  if (c.steps > 0) {
    training.steps = training.steps > 0 ? std::min(c.steps, training.steps) : c.steps;
  }
  training = cli::WithRecipeDefaults(*session_, training);
  training.seed = cli::DefaultTrainingSeed(*session_);
  const std::vector<std::string> methods = c.methods;
  std::vector<std::string> labels;
  for (const std::string& method : methods) {
    labels.push_back(method == teach::kBaselineMethod ? "Baseline" : "RECON");
  }
  // Until the job ends (ApplyFinishedJob): a studio closed meanwhile leaves the note behind.
  NoteTrainingStarted(session_->dir(), labels, training.steps);
  jobs_.Start(JobKind::kTraining,
              [this, training, methods](JobThread& jobs) -> std::function<void()> {
                std::string said = TrainMethods(jobs, *session_, training, methods);
                // The Train screen now shows the models saved in the session (session_view.cc).
                return [this, said = std::move(said)] { status_ = said; };
              });
}

void StudioCell::Apply(const ui::CancelTraining&) { jobs_.Cancel(); }

void StudioCell::Apply(const ui::CancelRollouts&) { jobs_.Cancel(); }

void StudioCell::Apply(const ui::RunRollouts& c) {
  RequireIdle("roll out");
  RequireNoEmergencyStop("roll out");
  const int tests = c.tests > 0 ? c.tests : options_.rollout_tests;
  jobs_.Start(JobKind::kRollouts, [this, tests](JobThread& jobs) -> std::function<void()> {
    std::string said = RollOutTrainedMethods(jobs, *session_, tests);
    return [this, said = std::move(said)] {
      ReloadPlayback();
      status_ = said;
    };
  });
}

void StudioCell::Apply(const ui::ShowRolloutFrame& c) { playback_->Show(c.scenario, c.frame); }

void StudioCell::Apply(const ui::WriteReport&) {
  RequireIdle("write the report");
  report_path_ = cli::WriteReportForSession(*session_);
  status_ = "Wrote " + report_path_ + ".";
}

void StudioCell::Apply(const ui::OpenReport&) {
  const std::string path = session_->ReportPath();
  if (!fs::exists(path)) throw UserError("write the report first: " + path + " does not exist");
  if (options_.open_command.empty()) {
    throw UserError("no program to open the report with; it is at " + path);
  }
  // Started, not waited for: an opener may run until the browser closes. A thread reaps it.
  const std::string program = options_.open_command;
  char* argv[] = {const_cast<char*>(program.c_str()), const_cast<char*>(path.c_str()), nullptr};
  pid_t pid = 0;
  if (const int error = posix_spawnp(&pid, program.c_str(), nullptr, nullptr, argv, environ);
      error != 0) {
    throw UserError("cannot open the report with '" + program + "' (" + std::strerror(error) +
                    "); it is at " + path);
  }
  auto opener = std::make_shared<Opener>();
  opener->program = program;
  opener->path = path;
  opener_ = opener;
  std::thread([pid, opener] {
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) status = -1;
    const std::lock_guard<std::mutex> lock(opener->mutex);
    opener->status = status;
  }).detach();
  status_ = "Opening " + path + " with " + program + "...";
}

void StudioCell::CheckOpener() {
  if (!opener_) return;
  std::optional<int> status;
  {
    const std::lock_guard<std::mutex> lock(opener_->mutex);
    status = opener_->status;
  }
  if (!status) return;  // still running: a browser opened by it, or the opener thinking
  const std::string program = opener_->program, path = opener_->path;
  opener_.reset();
  Changed();
  if (WIFEXITED(*status) && WEXITSTATUS(*status) == 0) {
    status_ = "Opened " + path + " with " + program + ".";
    return;
  }
  const std::string how =
      WIFEXITED(*status)
          ? "exit status " + std::to_string(WEXITSTATUS(*status))
          : (WIFSIGNALED(*status) ? "killed by signal " + std::to_string(WTERMSIG(*status))
                                  : std::string("it could not be waited for"));
  status_ = "The report was not opened.";
  AddError("'" + program + "' could not open the report (" + how +
           "; no browser set up?); it is at " + path);
}

void StudioCell::Apply(const ui::DismissErrors&) { errors_.clear(); }

void StudioCell::Apply(const ui::RescanDevices&) { scanner_.RescanNow(); }

void StudioCell::HoldEmergencyStop() {
  // The arm's own latch is what holds it; a world made while the e-stop is engaged gets it too.
  if (!estop_) return;
  if (safety::GuardedArm* arm = source_->GuardedArmOf(world_.get())) {
    arm->EngageEmergencyStop(estop_reason_);
  }
}

void StudioCell::Apply(const ui::EmergencyStop& c) {
  safety::GuardedArm* arm = source_->GuardedArmOf(world_.get());
  if (!c.engage) {
    if (arm != nullptr) arm->ReleaseEmergencyStop();
    estop_ = false;
    estop_reason_.clear();
    status_ = "E-stop released.";
    return;
  }
  estop_ = true;
  estop_reason_ = c.reason.empty() ? "e-stop pressed" : c.reason;
  // The arm stops now, through its guard, whichever cell: every command it gets from here on is
  // a stop until the release. What was being taught or tried is ended below; nothing
  // half-taught under an e-stop is kept.
  HoldEmergencyStop();
  teleop_input_ = {};
  teleop_command_ = {};
  key_ramp_.Clear();
  std::string stopped;
  if (TakeWaiting()) {
    // Nothing was taught yet: there is nothing to set aside.
    homing_take_ = false;
    recorder_.reset();
    replace_.reset();
    stopped = "; the take had not started";
  } else if (recorder_ && recorder_->recording()) {
    // What was taught so far is the teacher's to keep (as not done) or discard.
    recorder_->Stop();
    pending_take_ =
        "The e-stop stopped the take after " + std::to_string(recorder_->samples()) + " samples";
    stopped = "; the take so far is set aside: keep it (as not done) or discard it";
  }
  if (TrialMoving()) {
    AbortTrial("the e-stop (" + estop_reason_ + ")");
    stopped = "; the trial under way was stopped and not kept";
  }
  if (play_ && play_->recording()) {
    stopped = "; play recording stopped (" + std::to_string(play_done_) + " samples kept)";
    play_.reset();
    play_target_ = play_done_;
  }
  status_ = "E-STOP: " + estop_reason_ + stopped + ".";
}

}  // namespace recon::studio
