#pragma once

#include <array>
#include <string>
#include <vector>

namespace recon::teach {

/// The steps of teaching a task, in the order the studio lists them.
enum class Step { kCell, kBeacons, kCalibrate, kRecord, kPlay, kTrain, kRollouts, kReport };
constexpr int kNumSteps = 8;
constexpr std::array<Step, kNumSteps> kAllSteps = {
    Step::kCell, Step::kBeacons, Step::kCalibrate, Step::kRecord,
    Step::kPlay, Step::kTrain,   Step::kRollouts,  Step::kReport};

/// The step's name in the studio: "Cell", "Beacons", "Calibrate", "Record", "Play data", "Train",
/// "Rollouts", "Report".
const char* StepTitle(Step step);
/// One sentence telling the teacher what the step is for.
const char* StepPurpose(Step step);

/// The method names used in WorkflowFacts::trained_methods and evaluated_methods.
inline constexpr char kBaselineMethod[] = "baseline";
inline constexpr char kReconMethod[] = "recon";

/// Plain facts about the session and the cell, gathered by the app from the session
/// (engine/store/session.h), its checkpoints and rollouts, and the devices. The workflow is a pure
/// function of these, so a test can state a situation without a window, a cell or a disk.
struct WorkflowFacts {
  bool session_open = false;
  bool cell_connected = false;               ///< every required device reports connected
  std::vector<std::string> missing_devices;  ///< names of the devices not connected
  int beacons_required = 0;  ///< beacons the task's placement needs (1 for tabletop "plate")
  int beacons_assigned = 0;  ///< beacons the teacher has assigned to an object
  /// Objects the placement needs a beacon on that have none yet ("the plate"), for the reasons
  /// shown; may be left empty, the reasons then give a count.
  std::vector<std::string> unmarked_objects;
  bool calibration_present = false;
  bool calibration_passed = false;
  double calibration_rmse_m = 0;
  int demos = 0;            ///< usable committed demonstrations (not bad, not damaged)
  double demo_seconds = 0;  ///< teacher seconds of those demonstrations
  int min_demos = 1;        ///< needed before training; values below 1 count as 1
  int play_samples = 0;
  bool recording_demos = false;                ///< a demonstration recording is in progress
  bool recording_play = false;                 ///< a play data recording is in progress
  bool training = false;                       ///< training is in progress
  std::vector<std::string> trained_methods;    ///< kBaselineMethod, kReconMethod, ...
  std::vector<std::string> evaluated_methods;  ///< methods whose rollouts are of today's model
  /// Methods whose rollouts are of an older model (retrained since) or of a model trained on
  /// other data than the session now holds: they count as not evaluated.
  std::vector<std::string> outdated_evaluations;
  bool report_written = false;
  /// Non-empty when the session was taught in another cell than the one the studio drives now
  /// (a session of the simulated cell opened on a real cell, to try its trained policies on the
  /// real arm): why Beacons, Calibrate, Record and Play data are blocked here, e.g. "Taught in
  /// the simulated cell, recorded there"; the workflow adds the step to go to. Training, rollouts,
  /// trials and the report do not depend on where it was taught.
  std::string taught_elsewhere;
};

/// kBlocked: cannot be done yet (why_blocked says why). kReady: can be done now (for a done
/// step that can be redone, kDone wins). kBusy: its activity is running.
enum class StepState { kBlocked, kReady, kDone, kBusy };

/// How one step stands, for the studio's step list.
struct StepStatus {
  Step step = Step::kCell;
  StepState state = StepState::kBlocked;
  /// What the step holds, with counts, e.g. "1 of 1 beacon assigned", "4 demonstrations, 556 s".
  std::string summary;
  /// Empty unless kBlocked: which step to go to and what to do there, e.g. "Assign a beacon to
  /// the plate first (Beacons)". When the step to go to is itself blocked, its reason is given
  /// instead, so the teacher is always sent to a step they can act on.
  std::string why_blocked;
};

/// Evaluates every step, in order (one StepStatus per Step). The rules:
///
/// - Cell: done when a session is open and the cell is connected, ready otherwise (never blocked:
///   it is the entry point); the summary names the missing devices.
/// - Beacons: blocked until Cell is done; done when beacons_assigned >= beacons_required. A task
///   whose placement needs no beacon is done at once ("No beacons in this task (Baseline only)").
/// - Calibrate: blocked until Beacons is done; done when a calibration is present and passed;
///   ready, with the RMSE in the summary, when it failed. Done at once without beacons.
/// - Record: blocked until Calibrate is done (an uncalibrated beacon records wrong readings);
///   done when demos >= min_demos.
/// - Play data: blocked until Calibrate is done (it can be recorded before or after the
///   demonstrations); optional, so NextStep never points at it; done when play_samples > 0.
///   Play data only trains the beacon net, so without beacons it is done at once.
/// - Train: blocked until demos >= min_demos; done when both the Baseline and RECON are trained,
///   ready while only one is. Without beacons there is nothing for RECON to learn from, so only
///   the Baseline can be trained and Train is done once the Baseline is.
/// - Rollouts: blocked until a method is trained; done when every trained method is evaluated.
/// - Report: blocked until a session is open and holds a demonstration; done when written.
/// - A session taught elsewhere (taught_elsewhere): Beacons, Calibrate, Record and Play data are
///   blocked with that reason, whatever the session holds, sending the teacher to Rollouts once
///   a method is trained, else to Train when it can be done, else to Cell (another session);
///   the other steps follow their rules.
///
/// One activity at a time on the data: a running activity makes its own step kBusy
/// (recording_demos: Record, recording_play: Play data, training: Train), and blocks the steps
/// that would change the data it uses, with a reason to wait for it or stop it. Training blocks
/// Record and Play data; a recording blocks Train, the other recording step, and Beacons and
/// Calibrate (which would change what the readings being recorded mean).
std::vector<StepStatus> EvaluateWorkflow(const WorkflowFacts& facts);

/// What the teacher should do next: the running activity's step if one is busy (their attention
/// belongs there), else the first step that is ready and not done, skipping the optional Play
/// data; Report once everything is done; Cell when nothing can be done in this session here.
Step NextStep(const WorkflowFacts& facts);

/// Whether the teacher may open `step`'s screen now: true for a step that is not blocked, for
/// every step before NextStep (the teacher can always go back), and for a step blocked only
/// because an activity is running (its screen shows what it holds, its actions disabled). False
/// for a blocked step the teacher has not reached yet; EvaluateWorkflow says why.
bool CanOpen(const WorkflowFacts& facts, Step step);

}  // namespace recon::teach
