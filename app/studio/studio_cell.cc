#include "app/studio/studio_cell.h"

#include <algorithm>
#include <filesystem>

#include "app/studio/real_cell_source.h"
#include "app/studio/simulated_cell_source.h"
#include "app/studio/training_mark.h"
#include "app/studio/trial_run.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/teach/homing.h"
#include "engine/teach/session_setup.h"
#include "engine/teach/take_words.h"
#include "engine/worlds/ur5_arm.h"
#include "engine/worlds/world_factory.h"

namespace recon::studio {

namespace fs = std::filesystem;

namespace {

discovery::DiscoveryOptions ScanOptions(const StudioOptions& options) {
  discovery::DiscoveryOptions scan;
  scan.dev_dir = options.dev_dir;
  scan.robot_hosts = options.robot_hosts;
  return scan;
}

}  // namespace

StudioCell::StudioCell(const StudioOptions& options)
    : options_(options),
      recent_(options.recent_sessions_file.empty() ? RecentSessions::DefaultPath()
                                                   : options.recent_sessions_file),
      gamepad_(options.gamepad_paths),
      scanner_(ScanOptions(options), std::chrono::milliseconds(options.device_scan_ms)) {
  if (!recent_.problem().empty()) AddError(recent_.problem());
}

StudioCell::~StudioCell() = default;

void StudioCell::Start() {
  renderer_ = render::MujocoRendererFactory()();
  if (options_.cell_profile.empty()) {
    source_ = std::make_unique<SimulatedCellSource>(*renderer_);
  } else {
    source_ = std::make_unique<RealCellSource>(options_.cell_profile);
  }
  if (!source_->HasScriptedTeacher()) teleop_mode_ = ui::TeleopMode::kKeyboard;
  if (options_.session_dir.empty()) {
    picking_session_ = true;
    status_ = "Open a session, or create one in a new folder.";
    return;
  }
  OpenSessionAt(options_.session_dir);
}

void StudioCell::OpenSessionAt(const std::string& dir) {
  const bool exists = store::Session::Exists(dir);
  std::optional<store::SessionManifest> existing;
  if (exists) existing = store::LoadManifest((fs::path(dir) / "session.json").string());
  const std::string world = exists ? existing->world : options_.world;
  // The steps (a camera to click objects in, a UWB frame to calibrate) are the arm cell's.
  if (world != "tabletop") {
    throw UserError("the studio teaches in the tabletop cell; a " + world +
                    " session is recorded and trained from the command line (recon record, "
                    "recon train)");
  }
  // A session taught in the simulated cell may come to a real arm for trials of its policies
  // (sim-to-real), nothing else crosses: a real cell's scene has no simulation to record in.
  const bool trials_here = existing && existing->cell == "simulated" && source_->RunsTrials();
  if (exists && existing->cell != source_->Kind() && !trials_here) {
    throw UserError(dir + " was taught in " +
                    (existing->cell == "real"
                         ? "a real cell: open it with --cell PROFILE"
                         : "the simulated cell: open it without --cell (on a real cell it only "
                           "runs trials, and this cell has no arm)"));
  }
  if (session_ && fs::equivalent(session_->dir(), dir)) {
    picking_session_ = false;
    return;
  }
  std::optional<store::Session> opened;
  std::unique_ptr<worlds::World> made;
  if (exists) {
    opened.emplace(store::Session::Open(dir));
    if (!options_.calibration_file.empty()) opened->AttachCalibration(options_.calibration_file);
    made = source_->MakeSessionWorld(*opened);
  } else {
    teach::SessionSetup setup;
    setup.world_name = options_.world;
    setup.placement = teach::DefaultTeachingPlacement(options_.world);
    setup.image_size = options_.image_size;
    setup.seed = options_.seed;
    setup.beacon_noise_sigma =
        options_.beacon_noise_sigma.value_or(source_->DefaultBeaconNoise(options_.world));
    const std::vector<std::string> layouts = worlds::WorldLayouts(options_.world);
    setup.layout = layouts.empty() ? "" : options_.layout;
    setup.demo_noise_sigma =
        options_.demo_noise_sigma.value_or(source_->DefaultDemoNoise(options_.world));
    made = source_->MakeNewWorld(setup);
    store::SessionManifest manifest = teach::NewSessionManifest(setup, *made);
    source_->DescribeInto(manifest);
    opened.emplace(store::Session::Create(dir, manifest));
    if (!options_.calibration_file.empty()) {
      opened->AttachCalibration(options_.calibration_file);
      made = source_->MakeSessionWorld(*opened);  // with the calibration's UWB -> table transform
    }
  }
  // The new session is good: drop everything that belonged to the old one.
  recorder_.reset();
  pending_take_.clear();
  last_deleted_.reset();
  play_.reset();
  replace_.reset();
  report_path_.clear();
  trial_playback_ = {};
  episode_playback_ = {};
  saliency_models_.clear();
  world_ = std::move(made);
  HoldEmergencyStop();
  session_ = std::move(opened);
  // The teleop the teacher chose last in this session, where this cell offers it now (a
  // gamepad is chosen again once one is plugged in and picked).
  const std::string& remembered = session_->manifest().teleop;
  if (remembered == "keyboard") teleop_mode_ = ui::TeleopMode::kKeyboard;
  if (remembered == "scripted" && source_->HasScriptedTeacher()) {
    teleop_mode_ = ui::TeleopMode::kScripted;
  }
  ResetToNextScene();
  picking_session_ = false;
  current_step_ = teach::Step::kCell;
  playback_ = std::make_unique<RolloutPlayback>(session_->manifest(), session_->dir());
  ReloadPlayback();
  Changed();
  if (std::string problem = recent_.Add(session_->dir()); !problem.empty()) AddError(problem);
  status_ = std::string(exists ? "Opened" : "Created") + " session " + session_->dir() + ": " +
            session_->manifest().world + ", " + session_->manifest().cell + " cell.";
  if (!TrainingCutShort(session_->dir()).empty()) {
    status_ += " Its last training was cut short when the studio closed (see Train).";
  }
}

void StudioCell::Handle(const ui::StudioCommand& command) {
  Changed();  // whatever it does (or fails to do), the workflow is re-read
  const bool needs_session = !std::holds_alternative<ui::OpenSession>(command) &&
                             !std::holds_alternative<ui::ShowSessionPicker>(command) &&
                             !std::holds_alternative<ui::DismissErrors>(command) &&
                             !std::holds_alternative<ui::EmergencyStop>(command) &&
                             !std::holds_alternative<ui::RescanDevices>(command);
  if (needs_session && !session_) throw UserError("open or create a session first");
  std::visit([this](const auto& c) { Apply(c); }, command);
}

void StudioCell::Tick() {
  const Clock::time_point now = Now();
  PollGamepad(now);
  // Before a person's take: the countdown, and meanwhile the arm's return to its home pose,
  // where every take and every trial starts. The take starts once both are over; an arm already
  // home (the simulated cell's always is) delays it by nothing.
  if (homing_take_ && recorder_ && recorder_->recording() && now >= next_homing_) {
    StepTakeHoming(now);
  }
  if (recorder_ && recorder_->recording() && (now < take_starts_ || homing_take_)) {
    // Waiting: the arm does not move for the take yet.
  } else if (recorder_ && recorder_->recording()) {
    // A person teleoperating needs the real control rate, whatever --fast says.
    const bool paced = options_.real_time || teleop_mode_ != ui::TeleopMode::kScripted;
    if (!paced || now >= next_tick_) {
      next_tick_ = now + kControlPeriod;
      if (teleop_mode_ == ui::TeleopMode::kKeyboard) ShapeKeyboardTeleop(now);
      recorder_->Tick();
      arm_health_.Add(Seconds(now));
      if (const Sample* last = recorder_->last()) last_reading_ = last->b;
      beacon_health_.Add(Seconds(now), last_reading_);
      if (!recorder_->recording()) TakeEnded();
    }
  } else if (play_ && play_->recording()) {
    if (!options_.real_time || now >= next_tick_) {
      next_tick_ = now + kControlPeriod;
      play_->Tick();
      ShowPlaySample();
      if (!play_->recording()) CommitPlayChunk();
    }
  } else if (TrialMoving()) {
    TickTrial(now);
  } else if (calibrating_) {
    StepCalibration();  // it reads the beacons itself
  } else if (world_ && now >= next_beacon_) {
    // The beacons report at 10 Hz. Only read here when nothing records: a simulated reading
    // draws beacon noise from the world's generator, which a recording must have to itself so
    // that its scenario seed reproduces it exactly.
    next_beacon_ = now + kControlPeriod;
    if (auto reading = source_->IdleBeaconReading(*world_, *session_)) last_reading_ = *reading;
    beacon_health_.Add(Seconds(now), last_reading_);
  }
  if (playback_) playback_->Tick(now);
  ApplyFinishedJob();
  CheckOpener();
}

bool StudioCell::Busy() const {
  return Driving() || calibrating_ || trial_ != nullptr || jobs_.Running();
}

bool StudioCell::TakeWaiting() const {
  return recorder_ && recorder_->recording() && (homing_take_ || Now() < take_starts_);
}

bool StudioCell::Driving() const {
  return (recorder_ && recorder_->recording()) || (play_ && play_->recording()) || TrialMoving();
}

void StudioCell::AddError(const std::string& error) {
  if (errors_.empty() || errors_.back() != error) errors_.push_back(error);
}

void StudioCell::ReloadPlayback() {
  try {
    playback_->Reload();
  } catch (const UserError& e) {
    AddError(std::string("cannot play the rollouts back: ") + e.what());
  }
}

void StudioCell::ShapeKeyboardTeleop(Clock::time_point now) {
  const std::array<float, teach::KeyRamp::kChannels> share = key_ramp_.Period(Seconds(now));
  ui::TeleopInput shaped;
  shaped.screen_right = share[0];
  shaped.screen_up = share[1];
  shaped.raise = share[2];
  const ViewSize view{options_.view_width, options_.view_height};
  teleop_command_.velocity_m_s =
      source_->TeleopVelocity(*world_, shaped, view, teacher_view_, kTeleopSpeed_m_s);
  teleop_command_.wrist_turn_rad_s = share[3] * teach::kWristTurnSpeed_rad_s;
}

double StudioCell::Seconds(Clock::time_point t) const {
  return std::chrono::duration<double>(t - started_).count();
}

void StudioCell::ApplyFinishedJob() {
  const JobState job = jobs_.Take();
  // A training that ended here, whatever its end, was not cut short by the studio closing.
  if (job.kind == JobKind::kTraining && (job.finish || !job.error.empty()) && session_) {
    NoteTrainingEnded(session_->dir());
  }
  if (job.finish) job.finish();
  if (!job.error.empty()) AddError(job.error);
  if (job.finish || !job.error.empty()) Changed();
}

void StudioCell::ResetToNextScene() {
  // The scene the next take will be recorded in (the paper's protocol gives two takes one
  // configuration), not a scene of its own seed alone.
  teach::ShowSessionDemoScene(*world_, session_->manifest().seed, session_->NextDemoNumber());
}

void StudioCell::PollGamepad(Clock::time_point now) {
  if (gamepad_.Poll(now)) {
    Changed();
    if (!gamepad_.connected() && teleop_mode_ == ui::TeleopMode::kGamepad) {
      // The teacher's hand is gone: stop the arm where it is.
      teleop_input_ = {};
      teleop_command_.velocity_m_s.setZero();
      teleop_command_.wrist_turn_rad_s = 0;
      AddError(gamepad_.error() + "; the arm holds still");
    }
  }
  if (!gamepad_.connected() || teleop_mode_ != ui::TeleopMode::kGamepad ||
      !(recorder_ && recorder_->recording())) {
    return;
  }
  const teleop::GamepadTeleop& pad = gamepad_.command();
  ui::TeleopInput input;
  input.screen_right = pad.screen_right;
  input.screen_up = pad.screen_up;
  input.raise = pad.raise;
  input.turn = pad.turn;
  if (input != teleop_input_) Apply(input);
  if (pad.toggle_gripper) Apply(ui::ToggleGripper{});
  if (pad.keep) Commit();
}

teach::Teacher StudioCell::MakeTeacher() {
  // Scripted only where the cell has the scripted teacher: Start and SetTeleopMode see to it.
  if (teleop_mode_ == ui::TeleopMode::kScripted) return teach::ScriptedTeacher;
  // A person's teleop: one algorithm on the guarded arm of either cell.
  const safety::GuardedArm* arm = source_->GuardedArmOf(world_.get());
  if (arm == nullptr) throw UserError("this cell has no arm to teach with");
  return teach::CartesianTeleopTeacher(*arm, &teleop_command_, world_->StepSeconds());
}

std::string StudioCell::TeleopSource() const {
  // What the episode records as its source (EpisodeMeta::source): a stored value, not a label.
  switch (teleop_mode_) {
    case ui::TeleopMode::kScripted:
      return "scripted-teleop";
    case ui::TeleopMode::kKeyboard:
      return "keyboard-teleop";
    case ui::TeleopMode::kGamepad:
      return "gamepad-teleop";
  }
  return "teleop";
}

void StudioCell::StartDemo(int number, uint64_t seed) {
  teleop_input_ = {};
  teleop_command_ = {};
  key_ramp_.Clear();
  take_starts_ = Now();
  if (teleop_mode_ != ui::TeleopMode::kScripted) {
    take_starts_ += std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.countdown_s));
  }
  // A person's countdown is the teacher's time too (the ledger counts it).
  if (teleop_mode_ != ui::TeleopMode::kScripted && options_.countdown_s > 0) {
    session_->AddUnkeptTime(0, 0.0, options_.countdown_s);
  }
  // A person's take ends where a person ends it: the goal holds and the gripper is clear.
  recorder_ = std::make_unique<teach::DemoRecorder>(*world_, MakeTeacher(), TeleopSource(),
                                                    teleop_mode_ == ui::TeleopMode::kScripted
                                                        ? teach::DemoRecorder::TakeEnd::kScripted
                                                        : teach::DemoRecorder::TakeEnd::kPerson);
  teach::StartSessionTake(*recorder_, *world_, session_->manifest(), number, seed);
  // A simulated scene puts the arm at home itself; a real arm is where the last take left it.
  homing_take_ = teleop_mode_ != ui::TeleopMode::kScripted;
  take_homing_moved_ = false;
  take_homing_since_ = next_homing_ = Now();
}

bool StudioCell::StepTowardHome(const std::array<double, 6>& q_rad, Clock::time_point since,
                                Clock::time_point now) {
  const std::optional<std::array<double, 6>> v =
      teach::HomingVelocity(q_rad, worlds::Ur5Arm::kHome);
  if (!v) return true;
  if (now - since > kHomingTimeout) {
    throw UserError(
        "the arm did not reach its home pose within " +
        std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kHomingTimeout).count()) +
        " s (blocked, or in a protective stop?)");
  }
  std::vector<float> u(v->begin(), v->end());
  u.push_back(0.0f);  // the gripper opens on the way: every take and trial begins with it open
  world_->Step(u);
  return false;
}

void StudioCell::StepTakeHoming(Clock::time_point now) {
  safety::GuardedArm* arm = source_->GuardedArmOf(world_.get());
  try {
    if (arm == nullptr) throw UserError("the cell has no arm");
    if (StepTowardHome(arm->State().position_rad, take_homing_since_, now)) {
      homing_take_ = false;
      arm->Stop();
      // The teacher waits for the arm to get home: beyond the countdown, that is their time too.
      const double homing_s = std::chrono::duration<double>(now - take_homing_since_).count();
      if (take_homing_moved_ && homing_s > options_.countdown_s) {
        session_->AddUnkeptTime(0, 0.0, homing_s - options_.countdown_s);
      }
      return;
    }
    take_homing_moved_ = true;
    next_homing_ = now + kControlPeriod;
  } catch (const UserError& e) {
    homing_take_ = false;
    recorder_.reset();
    replace_.reset();
    try {
      if (arm != nullptr) arm->Stop();
    } catch (const UserError&) {
      // The arm is gone: its controller stopped it when the commands stopped.
    }
    Changed();
    AddError(std::string("the take did not start: while returning home, ") + e.what());
  }
}

void StudioCell::TakeEnded() {
  const bool scripted = teleop_mode_ == ui::TeleopMode::kScripted;
  // A take that ran out of time with the goal holding (the toast on the plate, let go) is done,
  // wherever the gripper stands.
  const bool done = scripted || world_->DemonstrationDone() || world_->TaskSucceeded();
  // A person is told what happened in their take: why it is not done, a regrasp, a long
  // stillness (a take left alone), so that keeping or discarding it is an informed choice.
  const std::string words = scripted ? "" : teach::TakeWords(*world_, recorder_->episode(), done);
  if (done) {
    Commit();
    if (!words.empty()) status_ += " In it, " + words + ".";
    return;
  }
  // A person ran out of time: whether an unfinished take is worth keeping is theirs to say.
  Changed();
  pending_take_ =
      "The take reached its " +
      std::to_string(static_cast<int>(world_->EpisodeLength() * world_->StepSeconds())) +
      " s limit before the task was done" + (words.empty() ? "" : ": " + words);
  status_ = pending_take_ + ": keep it (as not done) or discard it.";
}

void StudioCell::Commit() {
  Changed();
  pending_take_.clear();
  // A take recorded over still cost its teacher the time it took.
  if (replace_) {
    const double replaced_s = session_->Find(*replace_).meta.teaching_seconds;
    session_->AddUnkeptTime(1, replaced_s, 0.0);
  }
  const store::EpisodeEntry& e = session_->CommitDemo(recorder_->Take(), replace_);
  status_ = "Committed " + e.name + " (" + std::to_string(e.meta.num_samples) + " samples).";
  replace_.reset();
  recorder_.reset();
  ResetToNextScene();
}

void StudioCell::StartPlayChunk() {
  const int chunk =
      std::min(std::max(1, world_->PlaySamplesPerScenario()), play_target_ - play_done_);
  play_ = std::make_unique<teach::PlayRecorder>(*world_, source_->PlaySource());
  teach::StartSessionPlay(*play_, *world_, session_->manifest().seed, session_->NextPlayNumber(),
                          chunk);
}

void StudioCell::CommitPlayChunk() {
  Changed();
  const store::EpisodeEntry& e = session_->CommitPlay(play_->Take());
  play_done_ += static_cast<int>(e.meta.num_samples);
  status_ = "Committed " + e.name + " (" + std::to_string(e.meta.num_samples) + " play samples, " +
            std::to_string(play_done_) + " of " + std::to_string(play_target_) + ").";
  if (play_done_ < play_target_) {
    StartPlayChunk();
  } else {
    play_.reset();
    ResetToNextScene();
  }
}

void StudioCell::RequireIdle(const char* what) const {
  if (!pending_take_.empty()) {
    throw UserError(std::string("cannot ") + what + ": keep or discard the last take first (" +
                    pending_take_ + ")");
  }
  if (Busy()) throw UserError(std::string("cannot ") + what + " while something else runs");
}

void StudioCell::RequireTaughtHere(const char* what) const {
  const std::string& taught_in = session_->manifest().cell;
  if (taught_in == source_->Kind()) return;
  throw UserError(
      std::string("cannot ") + what + " here: " + session_->dir() + " was taught in the " +
      taught_in + " cell, and its data comes from there (" +
      (taught_in == "real" ? "recon-studio --cell PROFILE" : "recon-studio without --cell") +
      "); on this " + source_->Kind() + " cell its trained policies run trials (Rollouts)");
}

void StudioCell::RequireNoEmergencyStop(const char* what) const {
  if (estop_) {
    throw UserError(std::string("cannot ") + what + ": the e-stop is engaged (" + estop_reason_ +
                    "); release it first");
  }
}

}  // namespace recon::studio
