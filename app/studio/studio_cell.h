#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/studio/cell_source.h"
#include "app/studio/cell_view.h"
#include "app/studio/device_scanner.h"
#include "app/studio/gamepad_source.h"
#include "app/studio/job_thread.h"
#include "app/studio/recent_sessions.h"
#include "app/studio/rollout_playback.h"
#include "app/studio/studio_config.h"
#include "engine/store/real_trials.h"
#include "engine/store/session.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/teach/key_ramp.h"
#include "engine/teach/play_recorder.h"
#include "engine/teach/recorder.h"
#include "engine/teach/stream_health.h"
#include "engine/teach/workflow.h"
#include "engine/worlds/orbit_camera.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/world.h"
#include "ui/studio/studio_commands.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

struct TrialRun;

/// Everything the studio's cell thread owns: the session, the cell (simulated or real, through
/// CellSource), its world, the recorders, the jobs. It applies the UI's commands
/// (studio_cell_commands.cc), runs the cell loop (studio_cell.cc) and fills snapshots
/// (studio_cell_publish.cc). Not thread-safe: StudioController calls it from its cell thread
/// only (GL contexts and MuJoCo data belong to the thread that made them).
class StudioCell {
 public:
  using Clock = std::chrono::steady_clock;

  explicit StudioCell(const StudioOptions& options);
  ~StudioCell();

  /// Opens the cell the options name (the simulated one, or the real one of --cell) and the
  /// session, if the options name one (without, the studio starts at the session picker).
  void Start();
  /// Applies one command of the UI; UserError when it cannot be done now.
  void Handle(const ui::StudioCommand& command);
  /// One pass of the cell loop: a recording step, a play sample, the beacons, a finished job.
  void Tick();
  /// Starts a pass of the cell loop: on a SteppedClock (StudioOptions::clock), Now() is the
  /// clock's time at this call until the next.
  void BeginPass() {
    if (options_.clock) pass_time_ = options_.clock->Now();
  }
  /// The studio's time: the pass's on a SteppedClock, the steady clock's otherwise.
  Clock::time_point Now() const { return options_.clock ? pass_time_ : Clock::now(); }
  /// A recording or a job runs.
  bool Busy() const;
  /// Whether the cell thread itself drives something (a recording stepping the simulation):
  /// only then may its loop skip its sleep. A job (training, rollouts) runs on its own thread,
  /// and a loop that spun meanwhile took a core from it.
  bool Driving() const;
  /// Shown on screen until dismissed; the same error twice in a row is shown once.
  void AddError(const std::string& error);
  const std::vector<std::string>& errors() const { return errors_; }
  /// The snapshot: the session's side (rebuilt only after something changed it), then what
  /// moves by itself: the camera, the recording, the job's progress.
  void Publish(ui::StudioSnapshot& s);

 private:
  static constexpr auto kControlPeriod = std::chrono::milliseconds(100);  // the arm's 10 Hz
  /// Homing before a trial that takes longer than this stops it: the arm is blocked or stopped.
  static constexpr auto kHomingTimeout = std::chrono::seconds(30);
  static constexpr double kTeleopSpeed_m_s = 0.1;

  // The session (studio_cell.cc).
  /// Opens the session in `dir` (creating it there if the folder holds none) and makes its
  /// world. The session open until now stays open if this fails.
  void OpenSessionAt(const std::string& dir);
  /// Marks the session's side of the snapshot stale: after every command, commit and job.
  void Changed() { dirty_ = true; }
  /// Opens the rollouts' replay files for the playback; a damaged one is reported, not fatal.
  void ReloadPlayback();
  double Seconds(Clock::time_point t) const;
  /// The keyboard's command for the control period starting at `now` (KeyRamp): set just before
  /// each tick of a keyboard take.
  void ShapeKeyboardTeleop(Clock::time_point now);
  void ApplyFinishedJob();
  /// Resets the world to the scene of the next demonstration.
  void ResetToNextScene();

  // Recording (studio_cell.cc).
  void PollGamepad(Clock::time_point now);
  teach::Teacher MakeTeacher();
  std::string TeleopSource() const;
  /// Starts demonstration demo_<number> (a new one, or one being re-recorded) in its scene: a
  /// take of its configuration where the world groups them (World::DemosPerConfiguration).
  void StartDemo(int number, uint64_t seed);
  void Commit();
  /// A take's recording has ended by itself: kept when the task is done or the scripted teacher
  /// gave it; a person's take that hit the time limit waits for Keep or Discard.
  void TakeEnded();
  /// A chunk is one scenario's worth of play, seeded as `recon record --play` seeds it.
  void StartPlayChunk();
  /// One control period of the arm's return home before a person's take (teach::HomingVelocity);
  /// a fault or a joint too far from home ends the take before it started, and says why.
  void StepTakeHoming(Clock::time_point now);
  /// One control period of the arm's return to its home pose from `q_rad`, for a take or a trial
  /// (teach::HomingVelocity, the gripper opening): true, commanding nothing, once it is there.
  /// UserError for a joint too far from home or a return begun at `since` that is past
  /// kHomingTimeout.
  bool StepTowardHome(const std::array<double, 6>& q_rad, Clock::time_point since,
                      Clock::time_point now);
  /// A person's take is started but waits for its countdown or the arm's return home.
  bool TakeWaiting() const;
  /// Commits the play chunk just recorded and starts the next one while samples remain.
  void CommitPlayChunk();
  void RequireIdle(const char* what) const;
  /// For whatever moves the arm.
  void RequireNoEmergencyStop(const char* what) const;
  /// UserError naming `what` when the session was taught in another cell than this one (it
  /// came here for trials): its beacons, calibration and recordings belong to that cell.
  void RequireTaughtHere(const char* what) const;
  /// Engages the e-stop on the cell's arm if the studio's is engaged (a newly made world's arm).
  void HoldEmergencyStop();

  // The snapshot (studio_cell_publish.cc).
  /// Everything the snapshot shows of the session and the workflow (session_view.h).
  void RebuildSessionView();
  /// The live camera, the objects one can click and where the beacons read.
  void RenderView(ui::StudioSnapshot& s);
  /// The devices' measured rates and the beacons' health, from what actually arrived lately.
  void ShowDeviceHealth(ui::StudioSnapshot& s) const;
  /// What is plugged in, from the scanner's latest pass.
  void ShowConnected(ui::StudioSnapshot& s) const;
  /// The envelope the arm's commands pass, what it changed so far, and the e-stop.
  void ShowSafety(ui::StudioSnapshot& s) const;
  /// The latest play sample, for the Play screen.
  void ShowPlaySample();
  /// The Rollouts screen's playback, drawn only while it shows.
  void ShowPlayback(ui::StudioSnapshot& s);

  // The commands (studio_cell_commands.cc).
  void Apply(const ui::OpenStep& c);
  void Apply(const ui::AssignBeacon& c);
  void Apply(const ui::StartCalibration& c);
  void Apply(const ui::CancelCalibration& c);
  /// Makes the calibration at `path` the session's (the file is moved into it) and says so.
  void AttachCalibration(const std::string& path);
  /// One pass of a guided calibration (a real cell's); saves the fit once every place is taken.
  void StepCalibration();
  void Apply(const ui::StartRecording& c);
  void Apply(const ui::StopRecording& c);
  void Apply(const ui::DiscardRecording& c);
  void Apply(const ui::DeleteEpisode& c);
  void Apply(const ui::ReRecordEpisode& c);
  void Apply(const ui::MarkEpisodeBad& c);
  void Apply(const ui::RecordPlay& c);
  void Apply(const ui::StopPlay& c);
  void Apply(const ui::SetTeleopMode& c);
  void Apply(const ui::TeleopInput& c);
  void Apply(const ui::ShowSessionPicker& c);
  void Apply(const ui::OpenSession& c);
  void Apply(const ui::PlayRollouts& c);
  void Apply(const ui::StartTraining& c);
  void Apply(const ui::CancelTraining& c);
  void Apply(const ui::CancelRollouts& c);
  void Apply(const ui::UndoDelete& c);
  void Apply(const ui::OpenReport& c);
  void Apply(const ui::Quit&) {}         // the application closes the window (studio_main.cc)
  void Apply(const ui::AnswerClose&) {}  // so is this one
  void Apply(const ui::RunRollouts& c);
  void Apply(const ui::ShowRolloutFrame& c);
  void Apply(const ui::WriteReport& c);
  void Apply(const ui::DismissErrors& c);
  void Apply(const ui::RescanDevices& c);
  void Apply(const ui::EmergencyStop& c);
  void Apply(const ui::SetTeacherView& c);
  void Apply(const ui::ToggleGripper& c);

  // Trials on a real arm (studio_cell_trials.cc).
  void Apply(const ui::StartTrials& c);
  void Apply(const ui::RunTrial& c);
  void Apply(const ui::StopTrial& c);
  void Apply(const ui::JudgeTrial& c);
  void Apply(const ui::EndTrials& c);
  void Apply(const ui::ShowTrialFrame& c);
  // A recorded demonstration played back (studio_cell_episode_playback.cc).
  void Apply(const ui::ShowEpisodeFrame& c);
  /// The demonstration frame played back, with the saliency over it when on.
  void DrawEpisodeFrame();
  // What the trained methods look at (studio_cell_probe.cc).
  void Apply(const ui::RunProbe& c);
  void Apply(const ui::CancelProbe& c);
  void Apply(const ui::ShowProbeObject& c);
  void Apply(const ui::SetSaliency& c);
  /// The trial frame played back, with the saliency of its method's model over it when on.
  void DrawTrialFrame();
  /// Shows trial `number`'s layout (the test plan's scene number - 1) for the teacher to set up.
  void SetUpTrial(int number);
  /// The countdown, the return home, then one policy step per control period; the verdict once
  /// its time is up.
  void TickTrial(Clock::time_point now);
  /// One control period of the return home before a trial (teach::HomingVelocity); the policy
  /// starts once the arm is there. A fault, a joint too far from home or the timeout aborts it.
  void StepHoming(Clock::time_point now);
  /// The arm is home: the policy takes over.
  void StartPolicy();
  /// A fault or the e-stop during a trial: the arm stops, the trial is not kept, and the same
  /// trial waits to be set up and run again.
  void AbortTrial(const std::string& why);
  /// Stops the arm where it is (a real cell's world Reset), whether or not it is still there.
  void HoldArm();
  /// A trial is counting down, homing or running.
  bool TrialMoving() const;
  void ShowTrial(ui::StudioSnapshot& s) const;

  StudioOptions options_;
  Clock::time_point pass_time_ = options_.clock ? options_.clock->Now() : Clock::time_point{};
  RecentSessions recent_;
  bool picking_session_ = false;
  std::optional<store::Session> session_;
  /// Draws the simulated cell's live view and the rollouts' playback (the simulated scenes the
  /// policies ran in). Declared before source_, which may hold it.
  std::unique_ptr<worlds::SceneRenderer> renderer_;
  std::unique_ptr<CellSource> source_;  ///< the simulated cell or the real one (--cell)
  std::unique_ptr<worlds::World> world_;
  std::unique_ptr<teach::DemoRecorder> recorder_;
  std::optional<std::string> replace_;
  /// The last episode deleted, for Undo: its name, where it went in trash/, and its marks.
  struct Deleted {
    std::string name, trash_path;
    store::EpisodeFlags flags;
  };
  std::optional<Deleted> last_deleted_;
  ui::TeleopMode teleop_mode_ = ui::TeleopMode::kScripted;
  ui::TeleopInput teleop_input_;
  /// Where the teacher's 3-D view looks from; the arrows move the arm as it shows it.
  worlds::OrbitCamera teacher_view_ = DefaultTeacherView();
  teach::TeleopCommand teleop_command_;
  // The keyboard's keys as fine control: a tap moves a step, a held key speeds up.
  teach::KeyRamp key_ramp_;
  std::unique_ptr<teach::PlayRecorder> play_;
  std::unique_ptr<RolloutPlayback> playback_;
  GamepadSource gamepad_;
  int play_target_ = 0, play_done_ = 0;
  RgbImage play_image_;
  uint64_t play_image_frame_ = 0;
  std::vector<float> play_reading_;
  const Clock::time_point started_ = Now();
  Clock::time_point next_tick_ = Now();
  Clock::time_point take_starts_ = Now();  ///< a person's take, after its countdown
  Clock::time_point next_beacon_ = Now();
  std::vector<float> last_reading_;
  teach::StreamHealth camera_health_{30.0};
  teach::StreamHealth beacon_health_{10.0};
  teach::StreamHealth arm_health_{10.0};
  JobThread jobs_;
  /// A guided calibration runs on the cell thread (the teacher moves the beacon), not as a job.
  bool calibrating_ = false;
  ui::GuidedCalibrationView guided_calibration_;  ///< its live side, for the snapshot
  ui::StudioSnapshot session_view_;  ///< the session's side of the snapshot (RebuildSessionView)
  bool dirty_ = true;
  teach::Step current_step_ = teach::Step::kCell;
  std::vector<std::string> errors_;
  std::string status_;
  std::string report_path_;
  /// The report opener started last, reaped on a thread of its own: its exit says whether the
  /// report was opened (xdg-open exits non-zero when it finds no browser).
  struct Opener {
    std::mutex mutex;
    std::optional<int> status;  ///< waitpid's status once it exited
    std::string program, path;
  };
  std::shared_ptr<Opener> opener_;
  /// Says how the last opener ended, once it has.
  void CheckOpener();
  std::string probe_object_;  ///< whose heat maps the probe panel shows; "": the first probed
  ui::SaliencyMode saliency_ = ui::SaliencyMode::kOff;
  /// Frame `frame` of `frames` as the policy camera saw it, with the saliency of `method`'s
  /// model laid over it while the saliency is on (studio_cell_probe.cc).
  RgbImage SaliencyFrame(const store::TrialFrames& frames, size_t frame, const std::string& method);
  /// The models the saliency reads, per method, each with its checkpoint's time: loaded again
  /// once the method is retrained.
  struct SaliencyModel {
    std::filesystem::file_time_type written;
    learn::Policy policy;
  };
  std::map<std::string, SaliencyModel> saliency_models_;
  bool homing_take_ = false;        ///< a person's take waits for the arm to be home
  bool take_homing_moved_ = false;  ///< the arm was not home when the take was started
  Clock::time_point take_homing_since_, next_homing_;
  bool estop_ = false;
  /// Why the take in recorder_ was set aside unfinished (ui::StudioSnapshot::pending_take).
  std::string pending_take_;
  std::string estop_reason_;
  DeviceScanner scanner_;
  std::unique_ptr<TrialRun> trial_;
  ui::TrialPlaybackView trial_playback_;
  store::TrialFrames trial_frames_;  ///< the frames of the trial played back
  ui::EpisodePlaybackView episode_playback_;
  store::TrialFrames episode_frames_;  ///< the demonstration played back, frame by frame
};

}  // namespace recon::studio
