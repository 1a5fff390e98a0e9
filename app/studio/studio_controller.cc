#include "app/studio/studio_controller.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <optional>

#include "app/cli/session_report_builder.h"
#include "app/cli/session_training.h"
#include "app/cli/session_world.h"
#include "app/studio/cell_view.h"
#include "app/studio/device_scanner.h"
#include "app/studio/gamepad_source.h"
#include "app/studio/job_thread.h"
#include "app/studio/real_cell_source.h"
#include "app/studio/recent_sessions.h"
#include "app/studio/rollout_playback.h"
#include "app/studio/session_view.h"
#include "app/studio/studio_jobs.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/safety/guarded_arm.h"
#include "engine/store/session.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/teach/play_recorder.h"
#include "engine/teach/recorder.h"
#include "engine/teach/session_setup.h"
#include "engine/teach/stream_health.h"
#include "engine/teach/workflow.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/world_factory.h"

namespace recon::studio {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Everything the cell thread owns: the session, the simulated world, its camera, the recorder.
class StudioController::Cell {
 public:
  explicit Cell(const StudioOptions& options)
      : options_(options),
        recent_(options.recent_sessions_file.empty() ? RecentSessions::DefaultPath()
                                                     : options.recent_sessions_file),
        scanner_(ScanOptions(options), std::chrono::milliseconds(options.device_scan_ms)) {
    if (!recent_.problem().empty()) AddError(recent_.problem());
  }

  /// Opens or creates the session and the world, if the options name one (without, the studio
  /// starts at the session picker). Runs on the cell thread (GL contexts and MuJoCo data belong
  /// to the thread that made them).
  void Start() {
    view_ = render::MujocoRendererFactory()();
    if (!options_.cell_profile.empty()) {
      real_ = std::make_unique<RealCellSource>(options_.cell_profile);
      teleop_mode_ = "keyboard";  // a real cell has no scripted teacher
    }
    if (options_.session_dir.empty()) {
      picking_session_ = true;
      status_ = "Open a session, or create one in a new folder.";
      return;
    }
    OpenSessionAt(options_.session_dir);
  }

  /// Opens the session in `dir` (creating it there if the folder holds none) and makes its world.
  /// The session open until now stays open if this fails.
  void OpenSessionAt(const std::string& dir) {
    const bool exists = store::Session::Exists(dir);
    const std::string world =
        exists ? store::LoadManifest((fs::path(dir) / "session.json").string()).world
               : options_.world;
    // The steps (a camera to click objects in, a UWB frame to calibrate) are the arm cell's.
    if (world != "tabletop") {
      throw UserError("the studio teaches in the tabletop cell; a " + world +
                      " session is recorded and trained from the command line (recon record, "
                      "recon train)");
    }
    if (exists) {
      const std::string cell = store::LoadManifest((fs::path(dir) / "session.json").string()).cell;
      if (real_ && cell != "real") {
        throw UserError(dir + " was taught in the simulated cell: open it without --cell");
      }
      if (!real_ && cell == "real") {
        throw UserError(dir + " was taught in a real cell: open it with --cell PROFILE");
      }
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
      made = MakeWorld(*opened);
    } else {
      teach::SessionSetup setup;
      setup.world_name = options_.world;
      setup.placement = teach::DefaultTeachingPlacement(options_.world);
      setup.image_size = options_.image_size;
      setup.seed = options_.seed;
      // Simulated beacons' noise; real ones bring their own.
      setup.beacon_noise_sigma = options_.beacon_noise_sigma.value_or(
          real_ ? 0.0 : worlds::DefaultBeaconNoise(options_.world));
      const std::vector<std::string> layouts = worlds::WorldLayouts(options_.world);
      setup.layout = layouts.empty() ? "" : options_.layout;
      // A real arm is only perturbed when the teacher asks for it (--demo-noise).
      setup.demo_noise_sigma = options_.demo_noise_sigma.value_or(
          real_ ? 0.0 : worlds::DefaultDemoNoise(options_.world));
      made = real_ ? real_->MakeWorld(cli::WorldManifest(setup), "") : cli::MakeSetupWorld(setup);
      store::SessionManifest manifest = teach::NewSessionManifest(setup, *made);
      if (real_) real_->DescribeInto(manifest);
      opened.emplace(store::Session::Create(dir, manifest));
      if (!options_.calibration_file.empty()) {
        opened->AttachCalibration(options_.calibration_file);
        made = MakeWorld(*opened);  // with the calibration's UWB -> table transform
      }
    }
    // The new session is good: drop everything that belonged to the old one.
    recorder_.reset();
    play_.reset();
    replace_.reset();
    last_training_.clear();
    report_path_.clear();
    world_ = std::move(made);
    session_ = std::move(opened);
    world_->Reset(
        store::Session::ScenarioSeed(session_->manifest().seed, session_->NextDemoNumber(), false));
    picking_session_ = false;
    current_step_ = teach::Step::kCell;
    playback_ = std::make_unique<RolloutPlayback>(session_->manifest(), session_->dir());
    ReloadPlayback();
    Changed();
    if (std::string problem = recent_.Add(session_->dir()); !problem.empty()) AddError(problem);
    status_ = std::string(exists ? "Opened" : "Created") + " session " + session_->dir() + ": " +
              session_->manifest().world + ", " + session_->manifest().cell + " cell.";
  }

  void Handle(const ui::StudioCommand& command) {
    Changed();  // whatever it does (or fails to do), the workflow is re-read
    const bool needs_session = !std::holds_alternative<ui::OpenSession>(command) &&
                               !std::holds_alternative<ui::ShowSessionPicker>(command) &&
                               !std::holds_alternative<ui::DismissErrors>(command) &&
                               !std::holds_alternative<ui::EmergencyStop>(command) &&
                               !std::holds_alternative<ui::RescanDevices>(command);
    if (needs_session && !session_) throw UserError("open or create a session first");
    std::visit([this](const auto& c) { Apply(c); }, command);
  }

  /// One pass of the cell loop: a recording step, a play sample, the beacons, a finished job.
  void Tick() {
    const Clock::time_point now = Clock::now();
    PollGamepad(now);
    if (recorder_ && recorder_->recording()) {
      // A person teleoperating needs the real control rate, whatever --fast says.
      const bool paced = options_.real_time || teleop_mode_ != "scripted";
      if (!paced || now >= next_tick_) {
        next_tick_ = now + kControlPeriod;
        recorder_->Tick();
        arm_health_.Add(Seconds(now));
        if (const Sample* last = recorder_->last()) last_reading_ = last->b;
        beacon_health_.Add(Seconds(now), last_reading_);
        if (!recorder_->recording()) Commit();
      }
    } else if (play_ && play_->recording()) {
      if (!options_.real_time || now >= next_tick_) {
        next_tick_ = now + kControlPeriod;
        play_->Tick();
        ShowPlaySample();
        if (!play_->recording()) CommitPlayChunk();
      }
    } else if (world_ && now >= next_beacon_) {
      // The simulated DWM1001 reports at 10 Hz. Only read here when nothing records: a reading
      // draws beacon noise from the world's generator, which a recording must have to itself
      // so that its scenario seed reproduces it exactly.
      next_beacon_ = now + kControlPeriod;
      if (real_ && session_->manifest().calibration_file.empty()) {
        // Not calibrated: the world cannot map the beacon to the table yet; show that it
        // reports, in its own (UWB) frame.
        if (std::vector<float> raw = real_->RawBeaconReading(); !raw.empty()) last_reading_ = raw;
      } else {
        last_reading_ = world_->BeaconReading();
      }
      beacon_health_.Add(Seconds(now), last_reading_);
    }
    if (playback_) playback_->Tick(now);
    ApplyFinishedJob();
  }

  bool Busy() const {
    return (recorder_ && recorder_->recording()) || (play_ && play_->recording()) ||
           jobs_.Running();
  }
  /// Shown on screen until dismissed; the same error twice in a row is shown once.
  void AddError(const std::string& error) {
    if (errors_.empty() || errors_.back() != error) errors_.push_back(error);
  }
  const std::vector<std::string>& errors() const { return errors_; }

  /// The snapshot: the session's side (rebuilt only after something changed it, see dirty_),
  /// then what moves by itself: the camera, the recording, the job's progress.
  void Publish(ui::StudioSnapshot& s) {
    if (!session_) {
      s = {};
      ShowWorkflow(teach::WorkflowFacts{}, s);  // the steps say they wait for a session
      s.picking_session = true;
      s.recent_sessions = recent_.entries();
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
    s.picking_session = picking_session_;
    s.recent_sessions = recent_.entries();
    RenderView(s);
    const JobState job = jobs_.Peek();
    s.calibration.running = job.running && job.name == "calibration";
    s.calibration.points_collected = job.calibration_points;
    s.recording = recorder_ && recorder_->recording();
    s.recording_samples = recorder_ ? recorder_->samples() : 0;
    s.teleop = teleop_mode_;
    s.teleop_input = teleop_input_;
    if (real_) real_->ShowDevices(s);
    if (auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get())) {
      const Eigen::Vector3d grip = tabletop->arm().GripPosition();
      s.grip_m = {static_cast<float>(grip.x()), static_cast<float>(grip.y()),
                  static_cast<float>(grip.z())};
      s.gripper_closed = tabletop->arm().GripperClosed();
    }
    s.recording_play = play_ && play_->recording();
    s.play_recorded = play_done_ + (play_ ? play_->samples() : 0);
    s.play_target = play_target_;
    s.play_image = play_image_;
    s.play_image_frame = play_image_frame_;
    s.play_reading = play_reading_;
    ShowDeviceHealth(s);
    ShowConnected(s);
    ShowSafety(s);
    s.training = job.name == "training" ? job.training : last_training_;
    s.rollouts_running = job.running && job.name == "rollouts";
    s.rollout_tests = options_.rollout_tests;
    if (current_step_ == teach::Step::kRollouts && playback_) {
      // Drawn only while the Rollouts screen shows: two renders per step shown.
      try {
        playback_->Fill(s.rollouts, *view_, options_.view_width, options_.view_height);
        s.rollouts_playing = playback_->playing();
      } catch (const UserError& e) {
        // A scene's data is damaged: say so once and stop the playback, not the studio.
        AddError(std::string("cannot play the rollouts back: ") + e.what());
        playback_ = std::make_unique<RolloutPlayback>(session_->manifest(), session_->dir());
      }
    }
    s.report_path = report_path_;
    s.errors = errors_;
    s.status = job.running ? "Running " + job.name + "..." : status_;
  }

 private:
  /// The session's world: the simulated cell's, or the tabletop task over the real devices with
  /// the session's calibration.
  std::unique_ptr<worlds::World> MakeWorld(const store::Session& session) {
    const store::SessionManifest& m = session.manifest();
    if (!real_) return cli::MakeSessionWorld(m, m.placement);
    return real_->MakeWorld(m, m.calibration_file.empty()
                                   ? ""
                                   : (fs::path(session.dir()) / m.calibration_file).string());
  }

  /// Marks the session's side of the snapshot stale: after every command, commit and job.
  void Changed() { dirty_ = true; }

  /// Opens the rollouts' replay files for the playback; a damaged one is reported, not fatal.
  void ReloadPlayback() {
    try {
      playback_->Reload();
    } catch (const UserError& e) {
      AddError(std::string("cannot play the rollouts back: ") + e.what());
    }
  }

  double Seconds(Clock::time_point t) const {
    return std::chrono::duration<double>(t - started_).count();
  }

  void ApplyFinishedJob() {
    const JobState job = jobs_.Take();
    if (job.finish) job.finish();
    if (!job.error.empty()) AddError(job.error);
    if (job.finish || !job.error.empty()) Changed();
  }

  /// Everything the snapshot shows of the session and the workflow (session_view.h).
  void RebuildSessionView() {
    SessionViewInputs inputs;
    inputs.recording_demos = recorder_ && recorder_->recording();
    inputs.training = jobs_.RunningName() == "training";
    inputs.calibration_points = options_.calibration_points;
    inputs.gamepad = gamepad_.View();
    session_view_ = BuildSessionView(*session_, inputs);
  }

  /// The live camera, the objects one can click and where the beacons read; rendered only for
  /// the screens that show it, so training and rollouts get the CPU the others would take.
  void RenderView(ui::StudioSnapshot& s) {
    if (real_) {
      real_->ShowLive(session_->manifest(), last_reading_,
                      !session_->manifest().calibration_file.empty(), s);
      camera_health_.Add(Seconds(Clock::now()));
      return;
    }
    auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get());
    if (tabletop == nullptr) return;  // the other worlds have no camera
    switch (current_step_) {
      case teach::Step::kCell:
      case teach::Step::kBeacons:
      case teach::Step::kRecord:
      case teach::Step::kPlay:
        break;
      default:
        if (!(recorder_ && recorder_->recording())) return;
    }
    ShowTabletopView(*tabletop, *view_, options_.view_width, options_.view_height,
                     session_->manifest(), last_reading_, s);
    s.camera_frame = ++camera_frames_;
    camera_health_.Add(Seconds(Clock::now()));
  }

  /// The devices' measured rates and the beacons' health, from what actually arrived lately.
  void ShowDeviceHealth(ui::StudioSnapshot& s) const {
    const double now = Seconds(Clock::now());
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
      b.noise_m = beacon.noise;
    }
  }

  static discovery::DiscoveryOptions ScanOptions(const StudioOptions& options) {
    discovery::DiscoveryOptions scan;
    scan.dev_dir = options.dev_dir;
    scan.robot_hosts = options.robot_hosts;
    return scan;
  }

  /// What is plugged in, from the scanner's latest pass.
  void ShowConnected(ui::StudioSnapshot& s) const {
    uint64_t scans = 0;
    s.connected = scanner_.Latest(&scans);
    s.connected_scanned = scans > 0;
    s.connected_where = scanner_.Where();
  }

  /// The envelope the arm's commands pass, what it changed so far, and the e-stop.
  void ShowSafety(ui::StudioSnapshot& s) const {
    s.safety.estop = estop_;
    s.safety.estop_reason = estop_reason_;
    if (real_) return real_->ShowSafety(s.safety);
    const auto* tabletop = dynamic_cast<const worlds::Tabletop*>(world_.get());
    if (tabletop == nullptr) return;
    const safety::SafetyStats& stats = tabletop->safety_stats();
    s.safety.commands = stats.commands;
    s.safety.changed = stats.changed;
    s.safety.limits = safety::DescribeLimits(safety::SafetyLimits{});
  }

  /// The latest play sample, for the Play screen.
  void ShowPlaySample() {
    const PlaySample* sample = play_->last();
    if (sample == nullptr) return;
    play_image_ = ImageFromObservation(sample->y, session_->manifest().image_size);
    ++play_image_frame_;
    play_reading_ = sample->b;
    last_reading_ = sample->b;
    beacon_health_.Add(Seconds(Clock::now()), last_reading_);
  }

  /// Commits the play chunk just recorded and starts the next one while samples remain.
  void CommitPlayChunk() {
    Changed();
    const store::EpisodeEntry& e = session_->CommitPlay(play_->Take());
    play_done_ += static_cast<int>(e.meta.num_samples);
    status_ = "Committed " + e.name + " (" + std::to_string(e.meta.num_samples) +
              " play samples, " + std::to_string(play_done_) + " of " +
              std::to_string(play_target_) + ").";
    if (play_done_ < play_target_) {
      StartPlayChunk();
    } else {
      play_.reset();
      world_->Reset(store::Session::ScenarioSeed(session_->manifest().seed,
                                                 session_->NextDemoNumber(), false));
    }
  }

  /// A chunk is one scenario's worth of play, seeded as `recon record --play` seeds it.
  void StartPlayChunk() {
    const int chunk =
        std::min(std::max(1, world_->PlaySamplesPerScenario()), play_target_ - play_done_);
    play_ =
        std::make_unique<teach::PlayRecorder>(*world_, real_ ? "person-play" : "simulated-play");
    teach::StartSessionPlay(*play_, *world_, session_->manifest().seed, session_->NextPlayNumber(),
                            chunk);
  }

  /// Reads the gamepad and, when it drives the recording, turns its sticks into the same
  /// TeleopInput the keyboard sends.
  void PollGamepad(Clock::time_point now) {
    if (gamepad_.Poll(now)) {
      Changed();
      if (!gamepad_.connected() && teleop_mode_ == "gamepad") {
        // The teacher's hand is gone: stop the arm where it is.
        teleop_input_ = {};
        teleop_command_.velocity_m_s.setZero();
        AddError(gamepad_.error() + "; the arm holds still");
      }
    }
    if (!gamepad_.connected() || teleop_mode_ != "gamepad" ||
        !(recorder_ && recorder_->recording())) {
      return;
    }
    const teleop::GamepadTeleop& pad = gamepad_.command();
    ui::TeleopInput input;
    input.screen_right = pad.screen_right;
    input.screen_up = pad.screen_up;
    input.raise = pad.raise;
    input.close_gripper = teleop_input_.close_gripper != pad.toggle_gripper;
    if (input != teleop_input_) Apply(input);
    if (pad.keep) Commit();
  }

  teach::Teacher MakeTeacher() {
    if (real_) {
      if (teleop_mode_ == "scripted") {
        throw UserError(
            "a real cell has no scripted teacher: teach with the keyboard or a gamepad");
      }
      return real_->Teacher(&teleop_command_);
    }
    if (teleop_mode_ == "scripted") return teach::ScriptedTeacher;
    auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get());
    if (tabletop == nullptr) throw UserError("teleop needs the arm cell");
    return teach::CartesianTeleopTeacher(*tabletop, &teleop_command_);
  }

  std::string TeleopSource() const {
    return teleop_mode_ == "scripted" ? "scripted-teleop" : teleop_mode_ + "-teleop";
  }

  /// Starts demonstration demo_<number> (a new one, or one being re-recorded) in its scene: a
  /// take of its configuration where the world groups them (World::DemosPerConfiguration).
  void StartDemo(int number, uint64_t seed) {
    teleop_input_ = {};
    teleop_command_ = {};
    recorder_ = std::make_unique<teach::DemoRecorder>(*world_, MakeTeacher(), TeleopSource());
    teach::StartSessionTake(*recorder_, *world_, session_->manifest(), number, seed);
  }

  void Commit() {
    Changed();
    const store::EpisodeEntry& e = session_->CommitDemo(recorder_->Take(), replace_);
    status_ = "Committed " + e.name + " (" + std::to_string(e.meta.num_samples) + " samples).";
    replace_.reset();
    recorder_.reset();
    world_->Reset(
        store::Session::ScenarioSeed(session_->manifest().seed, session_->NextDemoNumber(), false));
  }

  void RequireIdle(const char* what) const {
    if (Busy()) throw UserError(std::string("cannot ") + what + " while something else runs");
  }
  /// For whatever moves the arm.
  void RequireNoEmergencyStop(const char* what) const {
    if (estop_) {
      throw UserError(std::string("cannot ") + what + ": the e-stop is engaged (" + estop_reason_ +
                      "); release it first");
    }
  }

  void Apply(const ui::OpenStep& c) { current_step_ = c.step; }
  void Apply(const ui::AssignBeacon& c) {
    RequireIdle("assign a beacon");
    session_->AssignBeacon(c.beacon, c.object);
    status_ = "Beacon " + c.beacon + " marks the " + c.object + ".";
  }
  void Apply(const ui::StartCalibration&) {
    RequireIdle("calibrate");
    if (real_) {
      throw UserError(
          "the Calibrate step runs the simulated cell's calibration only, for now: "
          "calibrate a real cell with 'recon calibrate --camera ... --out cal.json' "
          "and start the studio with --calibration cal.json");
    }
    const uint64_t seed = session_->manifest().seed;
    const int points = options_.calibration_points;
    const std::string dir = session_->dir();
    jobs_.Start("calibration", [this, seed, points, dir](JobThread& jobs) -> std::function<void()> {
      const std::string path = (fs::path(dir) / "calibration.new.json").string();
      CalibrateCell(jobs, seed, points, path);
      return [this, path] {
        session_->AttachCalibration(path);
        fs::remove(path);
        status_ = "Calibrated.";
      };
    });
  }
  void Apply(const ui::CancelCalibration&) { jobs_.Cancel(); }
  void Apply(const ui::StartRecording&) {
    RequireIdle("record");
    RequireNoEmergencyStop("record");
    const int number = session_->NextDemoNumber();
    StartDemo(number, store::Session::ScenarioSeed(session_->manifest().seed, number, false));
    status_ = teleop_mode_ == "scripted"
                  ? "Recording a demonstration (the scripted teacher)."
                  : "Recording a demonstration: drive the arm, Stop and keep when done.";
  }
  void Apply(const ui::StopRecording&) {
    if (recorder_ && recorder_->recording()) Commit();
  }
  void Apply(const ui::DiscardRecording&) {
    recorder_.reset();
    replace_.reset();
    status_ = "Recording discarded.";
  }
  void Apply(const ui::DeleteEpisode& c) {
    RequireIdle("delete an episode");
    session_->DeleteEpisode(c.name);
    status_ = "Moved " + c.name + " to the session's trash.";
  }
  void Apply(const ui::ReRecordEpisode& c) {
    RequireIdle("re-record");
    RequireNoEmergencyStop("re-record");
    const store::EpisodeEntry& e = session_->Find(c.name);
    StartDemo(e.number, e.meta.seed);
    replace_ = c.name;
    status_ = "Re-recording " + c.name + ".";
  }
  void Apply(const ui::MarkEpisodeBad& c) {
    RequireIdle("mark an episode");
    session_->MarkBad(c.name, c.bad);
  }
  void Apply(const ui::RecordPlay& c) {
    RequireIdle("record play data");
    RequireNoEmergencyStop("record play data");
    if (c.samples < 1) throw UserError("ask for at least one play sample");
    play_target_ = c.samples;
    play_done_ = 0;
    StartPlayChunk();
    status_ = "Recording " + std::to_string(c.samples) + " play samples.";
  }
  void Apply(const ui::StopPlay&) {
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
  void Apply(const ui::SetTeleopMode& c) {
    if (recorder_ && recorder_->recording()) {
      throw UserError("finish or discard the recording before changing the teleop");
    }
    if (c.mode == "gamepad" && !gamepad_.connected()) {
      throw UserError("no gamepad connected (looked for " + gamepad_.Places() + ")");
    }
    if (c.mode != "scripted" && c.mode != "keyboard" && c.mode != "gamepad") {
      throw UserError("unknown teleop '" + c.mode + "' (scripted, keyboard, gamepad)");
    }
    if (real_ && c.mode == "scripted") {
      throw UserError("a real cell has no scripted teacher: teach with the keyboard or a gamepad");
    }
    teleop_mode_ = c.mode;
  }
  void Apply(const ui::TeleopInput& c) {
    teleop_input_ = c;
    if (real_) {
      teleop_command_.velocity_m_s = real_->TeleopVelocity(c, kTeleopSpeed_m_s);
      teleop_command_.close_gripper = c.close_gripper;
      return;
    }
    auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get());
    if (tabletop == nullptr) return;
    teleop_command_.velocity_m_s =
        TeleopVelocity(*tabletop, c, options_.view_width, options_.view_height, kTeleopSpeed_m_s);
    teleop_command_.close_gripper = c.close_gripper;
  }
  void Apply(const ui::ShowSessionPicker& c) { picking_session_ = c.show && !Busy(); }
  void Apply(const ui::OpenSession& c) {
    RequireIdle("switch sessions");
    if (c.dir.empty()) throw UserError("type the session's folder first");
    OpenSessionAt(c.dir);
  }
  void Apply(const ui::PlayRollouts& c) { playback_->SetPlaying(c.playing); }

  void Apply(const ui::StartTraining& c) {
    RequireIdle("train");
    cli::SessionTrainingOptions training;
    // --train-steps caps what the screen asks for; 0 leaves both to the world's recipe.
    training.steps = options_.train_steps;
    if (c.steps > 0)
      training.steps = training.steps > 0 ? std::min(c.steps, training.steps) : c.steps;
    training = cli::WithRecipeDefaults(*session_, training);
    training.seed = cli::DefaultTrainingSeed(*session_);
    const std::vector<std::string> methods = c.methods;
    jobs_.Start("training", [this, training, methods](JobThread& jobs) -> std::function<void()> {
      std::vector<ui::TrainingView> finished = TrainMethods(jobs, *session_, training, methods);
      return [this, finished = std::move(finished)] {
        last_training_ = finished;
        status_ = "Trained.";
      };
    });
  }
  void Apply(const ui::CancelTraining&) { jobs_.Cancel(); }
  void Apply(const ui::RunRollouts& c) {
    RequireIdle("roll out");
    RequireNoEmergencyStop("roll out");
    if (real_) {
      throw UserError(
          "rollouts on a real arm are not run from the studio yet: the policies are "
          "trained; roll them out in the simulated cell's sessions");
    }
    const int tests = c.tests > 0 ? c.tests : options_.rollout_tests;
    jobs_.Start("rollouts", [this, tests](JobThread&) -> std::function<void()> {
      RollOutTrainedMethods(*session_, tests);
      return [this] {
        ReloadPlayback();
        status_ = "Rollouts done.";
      };
    });
  }
  void Apply(const ui::ShowRolloutFrame& c) { playback_->Show(c.scenario, c.frame); }
  void Apply(const ui::WriteReport&) {
    RequireIdle("write the report");
    report_path_ = cli::WriteReportForSession(*session_);
    status_ = "Wrote " + report_path_ + ".";
  }
  void Apply(const ui::DismissErrors&) { errors_.clear(); }
  void Apply(const ui::RescanDevices&) { scanner_.RescanNow(); }
  void Apply(const ui::EmergencyStop& c) {
    if (!c.engage) {
      if (real_) real_->EmergencyStop(false, "");
      estop_ = false;
      estop_reason_.clear();
      status_ = "E-stop released.";
      return;
    }
    estop_ = true;
    estop_reason_ = c.reason.empty() ? "e-stop pressed" : c.reason;
    if (real_) real_->EmergencyStop(true, estop_reason_);
    // The arm stops now. The simulated arm moves only while a recording steps it, so ending the
    // recording stops it; nothing half-taught under an e-stop is kept.
    teleop_input_ = {};
    teleop_command_ = {};
    std::string stopped;
    if (recorder_ && recorder_->recording()) {
      stopped = "; the demonstration being recorded was discarded";
      recorder_.reset();
      replace_.reset();
    }
    if (play_ && play_->recording()) {
      stopped = "; play recording stopped (" + std::to_string(play_done_) + " samples kept)";
      play_.reset();
      play_target_ = play_done_;
    }
    status_ = "E-STOP: " + estop_reason_ + stopped + ".";
  }

  static constexpr auto kControlPeriod = std::chrono::milliseconds(100);  // the arm's 10 Hz
  static constexpr double kTeleopSpeed_m_s = 0.1;

  StudioOptions options_;
  RecentSessions recent_;
  bool picking_session_ = false;
  std::optional<store::Session> session_;
  std::unique_ptr<RealCellSource> real_;  ///< the real cell, when the studio teaches in one
  std::unique_ptr<worlds::World> world_;
  std::unique_ptr<worlds::SceneRenderer> view_;
  std::unique_ptr<teach::DemoRecorder> recorder_;
  std::optional<std::string> replace_;
  std::string teleop_mode_ = "scripted";
  ui::TeleopInput teleop_input_;
  teach::TeleopCommand teleop_command_;
  std::unique_ptr<teach::PlayRecorder> play_;
  std::unique_ptr<RolloutPlayback> playback_;
  GamepadSource gamepad_{options_.gamepad_paths};
  int play_target_ = 0, play_done_ = 0;
  RgbImage play_image_;
  uint64_t play_image_frame_ = 0;
  std::vector<float> play_reading_;
  const Clock::time_point started_ = Clock::now();
  Clock::time_point next_tick_ = Clock::now();
  Clock::time_point next_beacon_ = Clock::now();
  std::vector<float> last_reading_;
  teach::StreamHealth camera_health_{30.0};
  teach::StreamHealth beacon_health_{10.0};
  teach::StreamHealth arm_health_{10.0};
  JobThread jobs_;
  ui::StudioSnapshot session_view_;  ///< the session's side of the snapshot (RebuildSessionView)
  bool dirty_ = true;
  std::vector<ui::TrainingView> last_training_;
  teach::Step current_step_ = teach::Step::kCell;
  std::vector<std::string> errors_;
  std::string status_;
  std::string report_path_;
  uint64_t camera_frames_ = 0;
  bool estop_ = false;
  std::string estop_reason_;
  DeviceScanner scanner_;
};

StudioController::StudioController(const StudioOptions& options)
    : options_(options), cell_(std::make_unique<Cell>(options)) {
  // The session and the world are made on the cell thread, which owns their GL context and
  // MuJoCo data; errors come back here so the app can report them before showing a window.
  std::promise<void> started;
  std::future<void> ready = started.get_future();
  cell_thread_ = std::thread([this, &started] {
    try {
      cell_->Start();
      ui::StudioSnapshot first;
      cell_->Publish(first);
      {
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        snapshot_ = std::move(first);
      }
      started.set_value();
    } catch (...) {
      cell_.reset();  // on this thread, like everything it made
      started.set_exception(std::current_exception());
      return;
    }
    RunCellThread();
    // The cell's GL contexts and MuJoCo data were made on this thread and must be freed here:
    // a context left current on an exited thread cannot be made current anywhere else.
    cell_.reset();
  });
  try {
    ready.get();
  } catch (...) {
    cell_thread_.join();
    throw;
  }
}

StudioController::~StudioController() {
  stop_ = true;
  if (cell_thread_.joinable()) cell_thread_.join();
}

void StudioController::RunCellThread() {
  constexpr auto kFrame = std::chrono::milliseconds(33);  // camera and snapshot at ~30 Hz
  auto next_publish = Clock::now();
  while (!stop_) {
    const std::vector<ui::StudioCommand> commands = commands_.Drain();
    for (const ui::StudioCommand& command : commands) {
      try {
        cell_->Handle(command);
      } catch (const std::exception& e) {
        cell_->AddError(e.what());  // shown on screen until dismissed
      }
    }
    try {
      cell_->Tick();
    } catch (const std::exception& e) {
      cell_->AddError(e.what());
    }
    const bool busy = cell_->Busy();
    if (Clock::now() >= next_publish || !commands.empty() || busy != published_busy_) {
      ui::StudioSnapshot fresh;
      try {
        cell_->Publish(fresh);
      } catch (const std::exception& e) {
        // A file of the session went bad under us (deleted, edited): say so, keep running.
        cell_->AddError(e.what());
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        snapshot_.errors = cell_->errors();
        published_busy_ = busy;
        handled_ += commands.size();
        next_publish = Clock::now() + kFrame;
        continue;
      }
      // The snapshot, whether anything runs and how many commands it reflects change together,
      // so Idle() and Settled() never pair an old state with a new count.
      std::lock_guard<std::mutex> lock(snapshot_mutex_);
      snapshot_ = std::move(fresh);
      published_busy_ = busy;
      handled_ += commands.size();
      next_publish = Clock::now() + kFrame;
    }
    if (!busy) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void StudioController::Push(ui::StudioCommand command) {
  {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    ++pushed_;
  }
  commands_.Push(std::move(command));
}

ui::StudioSnapshot StudioController::Snapshot() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return snapshot_;
}

bool StudioController::Idle() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return !published_busy_ && handled_ == pushed_;
}

bool StudioController::Settled() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return handled_ == pushed_;
}

}  // namespace recon::studio
