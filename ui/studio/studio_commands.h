#pragma once

#include <mutex>
#include <string>
#include <variant>
#include <vector>

#include "engine/teach/workflow.h"
#include "ui/studio/saliency_mode.h"
#include "ui/studio/teleop_mode.h"

namespace recon::ui {

// What the teacher asks for. The screens emit these; the studio's controller drains them on its
// own side and changes the session, the devices and the workers. Plain values, so a test can
// assert on exactly what a click asked for.

struct OpenStep {
  teach::Step step;
};
struct AssignBeacon {
  std::string beacon;
  std::string object;
};
struct StartCalibration {};
struct CancelCalibration {};
struct StartRecording {};
struct StopRecording {};
struct DiscardRecording {};
struct DeleteEpisode {
  std::string name;
};
/// Brings the last deleted episode back from the session's trash, with its marks.
struct UndoDelete {};
/// Opens the written report for the teacher (StudioOptions::open_command, a browser).
struct OpenReport {};
struct ReRecordEpisode {
  std::string name;
};
struct MarkEpisodeBad {
  std::string name;
  bool bad = true;
};
struct RecordPlay {
  int samples = 30;
};
struct StartTraining {
  std::vector<std::string> methods;
  int steps = 0;  ///< 0: the session's world's recipe (at most the studio's --train-steps)
};
struct CancelTraining {};
/// Stops the running rollouts; nothing of them is written (the rollouts from before stay).
struct CancelRollouts {};
/// Closes the studio (Session > Quit). The application acts on it, not the controller: the
/// window closes as with its close button, and a headless script ends there.
struct Quit {};
/// The answer to the question the window's close button raises while something runs
/// (StudioSnapshot::close_requested): stop it and close (`close`), or keep it running. The
/// application acts on it, as on Quit.
struct AnswerClose {
  bool close = false;
};
struct RunRollouts {
  int tests = 10;
};
/// Checks what the trained methods look at (cli::ProbeSession) as a job; CancelProbe stops it,
/// keeping the probe from before. `outcome` also rolls each method out whole from every place
/// (minutes rather than seconds).
struct RunProbe {
  bool outcome = false;
};
struct CancelProbe {};
/// Lays which pixels drive the action over the played-back frames (or stops).
struct SetSaliency {
  SaliencyMode mode = SaliencyMode::kOff;
};
/// Shows the heat maps of moving `object`.
struct ShowProbeObject {
  std::string object;
};
/// Shows frame `frame` of test scene `scenario` in the rollout playback (every method's rollout
/// of that scene, side by side) and pauses there.
struct ShowRolloutFrame {
  int scenario = 0;
  int frame = 0;
};
struct WriteReport {};
struct DismissErrors {};
/// The teleop that drives the next demonstration.
struct SetTeleopMode {
  TeleopMode mode = TeleopMode::kScripted;
};
/// What the teacher's keys (or sticks) ask for now, relative to the view as they see it: each
/// axis -1..1. The controller turns it into a velocity of the grip point in the table frame.
struct TeleopInput {
  float screen_right = 0;  ///< + moves the arm towards the view's right edge
  float screen_up = 0;     ///< + moves it towards the view's top edge (away)
  float raise = 0;         ///< + lifts the tool, - lowers it
  float turn = 0;          ///< + turns the wrist counter-clockwise seen from above
  bool operator==(const TeleopInput& o) const {
    return screen_right == o.screen_right && screen_up == o.screen_up && raise == o.raise &&
           turn == o.turn;
  }
  bool operator!=(const TeleopInput& o) const { return !(*this == o); }
};
/// Closes an open gripper or opens a closed one (Space, the gamepad's A) in a person's take. A
/// command of its own, not a field of TeleopInput: a state sent with the keys would be the
/// snapshot's, which lags the commands, and a key pressed just after Space undid it.
struct ToggleGripper {};
struct StopPlay {};
/// Where the teacher's 3-D view looks from (the Record screen's orbit and zoom); the cell keeps
/// it within worlds::OrbitCamera's limits.
struct SetTeacherView {
  float azimuth_deg = 0;
  float elevation_deg = -45;
  float distance_m = 1.3;
};
/// Plays the rollouts back (advancing ShowRolloutFrame's frame at the control rate) or pauses.
struct PlayRollouts {
  bool playing = true;
};
/// Shows the session picker (folder field, recent sessions) instead of the step's screen.
struct ShowSessionPicker {
  bool show = true;
};
/// Opens the session in `dir`, or creates a new one there; the current one is closed first.
struct OpenSession {
  std::string dir;
};
/// The e-stop (the status bar's button, or F12): engaging it stops the arm at once, ends a
/// demonstration (set aside for the teacher to keep or discard) or a play recording, and refuses
/// everything that would move the arm until it is released.
struct EmergencyStop {
  bool engage = true;
  std::string reason = "e-stop pressed";
};
/// Looks for plugged-in devices now instead of at the next periodic scan.
struct RescanDevices {};

/// Trials of a trained policy on a real arm (a real cell's Rollouts step), a lab's protocol: the
/// screen shows the next test layout, the teacher sets it up and runs the trial, the policy runs
/// through the safety envelope until its time is up or the teacher stops it, the teacher judges
/// it, and the next one follows.
struct StartTrials {
  std::string method;  ///< "baseline" or "recon"
  int trials = 0;      ///< how many; 0: the studio's --rollout-tests
};
/// The layout is set up: run the trial (after the countdown).
struct RunTrial {};
/// Stops the policy now (the arm stops); a running trial is then judged as it stands.
struct StopTrial {};
/// The teacher's verdict on the trial that just ran, and why.
struct JudgeTrial {
  bool succeeded = false;
  std::string reason;
};
/// No more trials now; the judged ones stay in the session.
struct EndTrials {};
/// Shows frame `frame` of a judged trial's camera frames (what its policy saw).
struct ShowTrialFrame {
  std::string method;
  int number = 0;
  int frame = 0;
};

/// Shows frame `frame` of the recorded demonstration `episode` (what the camera saw while it
/// was taught), with the saliency of `method`'s model over it while the saliency is on (empty:
/// the first trained method). An empty `episode` closes the playback.
struct ShowEpisodeFrame {
  std::string episode;
  int frame = 0;
  std::string method;
};

using StudioCommand =
    std::variant<OpenStep, AssignBeacon, StartCalibration, CancelCalibration, StartRecording,
                 StopRecording, DiscardRecording, DeleteEpisode, ReRecordEpisode, MarkEpisodeBad,
                 RecordPlay, StartTraining, CancelTraining, RunRollouts, CancelRollouts,
                 ShowRolloutFrame, WriteReport, DismissErrors, SetTeleopMode, TeleopInput, StopPlay,
                 PlayRollouts, ShowSessionPicker, OpenSession, EmergencyStop, RescanDevices, Quit,
                 AnswerClose, UndoDelete, OpenReport, SetTeacherView, ToggleGripper, StartTrials,
                 RunTrial, StopTrial, JudgeTrial, EndTrials, ShowTrialFrame, ShowEpisodeFrame,
                 RunProbe, CancelProbe, ShowProbeObject, SetSaliency>;

/// Commands from the UI thread to the controller; safe to push and drain from different threads.
class CommandQueue {
 public:
  void Push(StudioCommand command) {
    std::lock_guard<std::mutex> lock(mutex_);
    commands_.push_back(std::move(command));
  }
  std::vector<StudioCommand> Drain() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<StudioCommand> out;
    out.swap(commands_);
    return out;
  }

 private:
  std::mutex mutex_;
  std::vector<StudioCommand> commands_;
};

}  // namespace recon::ui
