#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/image.h"
#include "engine/teach/workflow.h"
#include "ui/studio/saliency_mode.h"
#include "ui/studio/studio_commands.h"
#include "ui/studio/teleop_mode.h"

namespace recon::ui {

/// A device of the cell as the Cell screen shows it.
struct DeviceView {
  std::string role;    ///< "camera", "arm", "beacons", "teleop"
  std::string kind;    ///< "simulated", "dwm1001", ...
  std::string detail;  ///< port, model, resolution
  bool connected = false;
  double rate_hz = 0;      ///< updates per second lately (0: not streaming)
  std::string last_error;  ///< empty when healthy
};

/// A device plugged into this computer (devices/discovery, listed without opening it), as the
/// Cell screen's "Connected" table shows it.
struct ConnectedDeviceView {
  std::string kind;      ///< "beacon", "camera", "gamepad", "robot"
  std::string path;      ///< /dev/ttyACM0, /dev/video0, host:port
  std::string identity;  ///< the USB name, the joystick's name; empty when unknown
  bool usable = false;
  std::string detail;
};

/// The safety envelope every arm command passes, and what it did.
struct SafetyView {
  std::string limits;  ///< e.g. "1 rad/s, 5 rad/s^2, tool floor 5 mm, watchdog 200 ms"
  int64_t commands = 0;
  int64_t changed = 0;  ///< commands the envelope limited or stopped
  bool estop = false;   ///< the e-stop is engaged
  std::string estop_reason;
};

/// An object on the table a beacon can mark, with where the camera sees it.
struct ObjectView {
  std::string name;                ///< "plate", "bowl", "toast"
  float pixel_x = 0, pixel_y = 0;  ///< in the camera image
  /// False when the cell does not know where the object is (a real cell): then it is offered
  /// in the list only, not drawn on the camera view.
  bool located = true;
};

/// A beacon as the Beacons screen shows it.
struct BeaconView {
  std::string name;    ///< "plate"
  std::string object;  ///< the object it is assigned to; empty when not yet assigned
  std::string quantity;
  std::string unit;
  std::vector<float> reading;  ///< the latest reading (empty before the first)
  /// Where the reading projects into the camera image, for the overlay.
  std::optional<std::array<float, 2>> pixel;
  /// What the overlay writes under the marker; empty: "beacon <name>".
  std::string label;
  double rate_hz = 0;           ///< updates per second
  double dropout_fraction = 0;  ///< missed updates over the last seconds
  double noise_m = 0;           ///< measured spread of the readings per axis (the last 3 s)
};

/// What the gripper does with what it should pick up, as the Record screen's readout says it.
enum class GripState {
  kUnknown,          ///< the cell cannot tell (a real gripper without object detection)
  kOpen,             ///< open
  kClosing,          ///< the fingers are on their way in
  kHolding,          ///< holding the object (GripView::object)
  kClosedOnNothing,  ///< the fingers shut without the object between them
};

/// The arm's grip as a teacher needs it to grasp: where it is, how high, and what it holds.
struct GripView {
  GripState state = GripState::kUnknown;
  std::string object;  ///< what the task picks up ("toast"); empty when the cell does not say
  /// The grip point's heights above the table at which closing holds the object (both 0 when
  /// the cell does not know).
  float grasp_min_m = 0, grasp_max_m = 0;
  /// Where the object lies across the open fingers (Ur5Arm::AlignmentWith): its centre off the
  /// jaw's closing axis, and how far it may be for a close to hold it; known = false when the
  /// cell cannot tell.
  bool alignment_known = false;
  float off_axis_m = 0, off_axis_window_m = 0;
  float beyond_pads_m = 0, beyond_pads_window_m = 0;
  float object_distance_m = 0;  ///< from the grip point to the object's centre, in the plane
  /// How far the wrist is turned from home (degrees, counter-clockwise from above), and its limit.
  float wrist_turn_deg = 0, wrist_limit_deg = 90;
};

/// The teacher's 3-D view of the cell: a camera they orbit and zoom (the simulated cell's free
/// camera), with the grip's drop line and shadow drawn in. Unavailable on a real cell.
struct TeacherView {
  bool available = false;
  RgbImage image;
  uint64_t frame = 0;  ///< grows with every new image
  float azimuth_deg = 0, elevation_deg = 0, distance_m = 0;
  /// Where the view shows the grip point, and the spot under it where the drop line lands (on
  /// the toast, the plate or the table), in image pixels.
  std::array<float, 2> grip_pixel{}, spot_pixel{};
  /// The ends of the jaw's closing axis drawn through the spot (where the fingers close), in
  /// image pixels.
  std::array<float, 4> jaw_pixels{};
};

/// A teleop the Record screen offers, and whether it can be used now.
struct TeleopChoice {
  TeleopMode mode = TeleopMode::kScripted;
  bool available = true;
  std::string why_not;  ///< e.g. "no gamepad connected"
};

/// A committed demonstration as the Record screen lists it.
struct EpisodeView {
  std::string name;
  int samples = 0;
  double seconds = 0;
  bool succeeded = false;
  bool bad = false;
  std::string split;
  std::string problem;  ///< non-empty for a damaged episode
};

/// Calibration as the Calibrate screen shows it.
/// What a real cell's calibration shows while it runs, paced by the teacher who moves the beacon
/// (cell::GuidedCalibration): what to do now and what the devices see of it.
struct GuidedCalibrationView {
  int points_taken = 0, points_target = 0;
  std::string prompt;
  bool tag_seen = false;
  std::array<float, 2> tag_pixel{0, 0};  ///< the beacon's tag in the camera image
  /// The places taken so far, where the camera sees them.
  std::vector<std::array<float, 2>> taken_pixel;
  std::vector<float> beacon_uwb_m;  ///< the newest reading, the beacons' own frame; empty: none
  bool beacon_silent = false;
  float held_fraction = 0;  ///< 0 to 1 through the hold that takes a place
};

struct CalibrationView {
  bool running = false;
  int points_collected = 0;
  int points_target = 12;
  bool present = false;
  bool passed = false;
  double rmse_m = 0, p95_m = 0, threshold_m = 0.10;
  std::vector<double> residual_m;  ///< per point
  std::vector<bool> inlier;
  /// Set while a calibration paced by the teacher runs (a real cell's).
  std::optional<GuidedCalibrationView> guided;
};

/// One training run (a method) as the Train screen shows it.
struct TrainingView {
  std::string method;  ///< "baseline" or "recon"
  std::string label;   ///< "Baseline", "RECON (Play)"
  bool running = false;
  bool done = false;
  int step = 0, steps = 0;
  double seconds = 0;
  std::vector<float> loss_step, action_loss, beacon_loss, total_loss;
  /// What the losses measure: "nll" (Gaussian negative log-likelihood of standardised targets,
  /// nats) or "mse-sample" (squared error of a sample).
  std::string loss = "nll";
  std::string error;
  /// Why a saved model no longer matches the session (cli::TrainingStaleness), "" when it does.
  std::string out_of_date;
};

/// Where a trial on a real arm stands (StartTrials).
enum class TrialPhase {
  kNone,       ///< no trials under way
  kSetUp,      ///< the teacher sets the layout up, then runs the trial
  kCountdown,  ///< the arm moves when it ends
  kHoming,     ///< the arm returns to its home pose, where every demonstration began
  kRunning,    ///< the policy drives the arm
  kJudge,      ///< it ended: the teacher says whether it succeeded
};

/// The trial protocol as the Rollouts screen of a real cell shows it.
struct TrialView {
  TrialPhase phase = TrialPhase::kNone;
  std::string method, label;
  int number = 0;           ///< the trial's number in its method's log (1, 2, ...)
  int first = 0, last = 0;  ///< the trials of this run
  uint64_t scene_seed = 0;  ///< the test scene whose layout is set up
  struct Object {
    std::string name;
    std::array<float, 2> table_m{0, 0};
    std::optional<std::array<float, 2>> pixel;  ///< where it goes in the live camera image
  };
  std::vector<Object> layout;
  double countdown_s = 0;
  float homing_progress = 0;  ///< 0..1 of the way home (kHoming)
  int step = 0, max_steps = 0;
  bool stopped = false;  ///< the teacher stopped it (kJudge)
  std::string message;   ///< what happened to the last trial (a fault, the e-stop), if anything
};

/// A method's judged trials on a real arm, from the session.
struct RealTrialsView {
  std::string method, label;
  int successes = 0;
  struct Row {
    int number = 0;
    bool succeeded = false;
    bool stopped = false;
    std::string reason;
    bool has_frames = false;
  };
  std::vector<Row> trials;
  std::string out_of_date;  ///< why the trials are not of the current model, "" when they are
};

/// A judged trial's frames, played back (ShowTrialFrame).
struct TrialPlaybackView {
  std::string method;
  int number = 0;  ///< 0: none shown
  int frame = 0, frames = 0;
  RgbImage image;
  uint64_t image_frame = 0;  ///< grows with every new image
};

/// A recorded demonstration played back on the Record screen (ShowEpisodeFrame): what the
/// camera saw while it was taught, and which pixels a trained policy would act on.
struct EpisodePlaybackView {
  std::string episode;  ///< "demo_0"; empty: none shown
  int frame = 0, frames = 0;
  std::string method;  ///< whose saliency is laid over the frame while it is on
  /// The trained methods to choose from: (method, label).
  std::vector<std::pair<std::string, std::string>> methods;
  RgbImage image;
  uint64_t image_frame = 0;  ///< grows with every new image
};

/// One method's rollouts as the Rollouts screen shows them.
struct RolloutView {
  std::string method;
  std::string label;
  std::string metric_name;
  double metric_mean = 0, metric_sem = 0;
  bool has_success = false;
  double success_rate = 0;
  int tests = 0;
  /// Why these rollouts no longer describe the session (cli::RolloutStaleness): the model was
  /// retrained since, or trained on data that has changed since; empty when they do.
  std::string out_of_date;
  // The playback of one test scene (all methods show the same scene and step).
  bool has_replay = false;  ///< rollouts/<method>.replay.h5 exists and opened
  int scenario = 0;         ///< which test scene the playback shows
  int frame = 0, frames = 0;
  uint64_t scenario_seed = 0;
  double scenario_metric = 0;
  bool scenario_succeeded = false;
  /// Why each test scene failed, in the summary's order (worlds::DescribeFailure; "" for a
  /// success or a world that cannot say).
  std::vector<std::string> scene_failures;
  RgbImage frame_image;   ///< the playback's current frame
  uint64_t frame_id = 0;  ///< changes whenever frame_image does
};

/// What the trained methods look at (the Rollouts step's "Check what it looks at", the same as
/// `recon eval --probe`): each object moved over the table with everything else held.
struct ProbeView {
  bool running = false, cancelling = false;
  std::string phase;  ///< "moving objects", "rendering read-out scenes"
  int done = 0, total = 0;
  bool present = false;  ///< the session holds a probe
  struct Row {
    std::string label, object;
    /// None when nothing was moved (a real cell's session: read out on its recorded frames).
    std::optional<double> action_change_per_10cm, feature_change_per_10cm;
    std::optional<double> readout_r2;    ///< none where the object never moved
    std::optional<double> success_rate;  ///< with whole rollouts from every place
  };
  std::vector<Row> rows;
  bool rolled_out = false;  ///< the probe rolled each method out from every place
  /// Per method, what its action moves with most: "RECON (Play) moves most with the plate".
  std::vector<std::string> verdicts;
  std::string note;                  ///< the scene, the grid, the read-out's scenes
  std::string out_of_date;           ///< why it is not of the current models; "" if it is
  std::vector<std::string> objects;  ///< every object probed
  std::string shown_object;          ///< whose heat maps `maps` are
  /// The shown object's heat map per method: action change per cell (row-major from y_min, NaN
  /// where the object would overlap another), on one colour scale (0 to scale_max).
  struct Map {
    std::string label;
    int nx = 0, ny = 0;
    std::array<float, 4> bounds = {0, 0, 0, 0};  ///< x_min, x_max, y_min, y_max (metres)
    std::vector<float> values;
    float scale_max = 0;
    std::vector<std::pair<std::string, std::array<float, 2>>> markers;  ///< objects' places
  };
  std::vector<Map> maps;
  /// With whole rollouts: per method, where they succeeded (1) or failed (0) with the shown
  /// object there (scale_max 1).
  std::vector<Map> outcome_maps;
};

/// Everything the studio's screens draw, copied from the engine side once per frame under a
/// short lock. The UI reads only this and answers with commands (studio_commands.h): it never
/// touches a session, a device or a trainer.
struct StudioSnapshot {
  // Session and workflow.
  bool session_open = false;
  bool picking_session = false;              ///< the session picker replaces the step's screen
  std::vector<std::string> recent_sessions;  ///< most recent first
  std::string session_dir;
  std::string world;
  std::vector<teach::StepStatus> steps;  ///< teach::EvaluateWorkflow of the facts
  std::array<bool, teach::kNumSteps> can_open{};
  teach::Step current_step = teach::Step::kCell;
  teach::Step next_step = teach::Step::kCell;

  // Cell.
  std::string cell_kind = "simulated";  ///< the cell the session was taught in (its manifest's)
  /// The cell this studio drives ("simulated", or "real" with --cell): another than cell_kind
  /// for a session taught in the simulated cell and opened on a real one to run trials.
  std::string studio_cell = "simulated";
  std::vector<DeviceView> devices;
  std::vector<ConnectedDeviceView> connected;  ///< what is plugged in (scanned every 2 s)
  bool connected_scanned = false;              ///< false until the first scan finished
  std::string connected_where;                 ///< where it looks, e.g. "/dev"
  SafetyView safety;
  RgbImage camera;  ///< the live camera frame (empty when none)
  uint64_t camera_frame = 0;
  std::vector<ObjectView> objects;
  std::vector<BeaconView> beacons;

  CalibrationView calibration;

  // Recording.
  bool recording = false;
  int recording_samples = 0;
  int recording_max_samples = 0;  ///< where a take ends by itself (the world's episode length)
  double recording_step_s = 0.1;  ///< seconds per sample (the control period)
  double countdown_s = 0;         ///< left before a person's take starts (0: it runs)
  bool take_homing = false;       ///< the arm returns home before a person's take starts
  /// A take that ended without the task done (it reached the time limit, or the e-stop stopped
  /// it): why, while it waits for the teacher to keep it (as not done) or discard it; "" when
  /// there is none.
  std::string pending_take;
  std::string undo_delete;  ///< the episode "Undo delete" brings back; "" when there is none
  TeleopMode teleop = TeleopMode::kScripted;
  std::vector<TeleopChoice> teleop_choices;
  TeleopInput teleop_input;           ///< what the controller drives the arm by now (keys, sticks)
  std::array<float, 3> grip_m{};      ///< the arm's grip point in the table frame
  std::array<float, 2> grip_pixel{};  ///< and where the camera view shows it
  /// The jaw's closing axis through the point under the grip, as the camera view shows it (both
  /// ends, image pixels; all 0 when the cell cannot tell).
  std::array<float, 4> jaw_camera_pixels{};
  bool gripper_closed = false;
  GripView grip;
  TeacherView teacher_view;
  std::vector<EpisodeView> episodes;
  /// Said when the good demonstrations come from more than one teleop (teach::TeacherMixWarning).
  std::string teacher_mix_warning;
  /// Said when some kept takes are much slower than the others (teach::SlowTakesWarning).
  std::string slow_takes_warning;
  /// Everything the teacher spent so far: kept and discarded takes, countdowns, play, beacons.
  double teacher_seconds = 0;
  double teacher_discarded_seconds = 0, teacher_countdown_seconds = 0;
  int teacher_discarded_takes = 0;
  /// Its parts (the session's teaching ledger): a beacon's placement counts before any take.
  double teacher_demo_seconds = 0, teacher_play_seconds = 0, teacher_placement_seconds = 0;

  // Play data.
  int play_samples = 0;  ///< committed
  /// Play samples recorded in one scene before the next puts the objects, the plate and its
  /// beacon too, somewhere else: a chunk (World::PlaySamplesPerScenario) per demonstration of a
  /// configuration (World::DemosPerConfiguration), as play chunks follow the takes' scenes.
  /// 0: not known.
  int play_scene_samples = 0;
  bool recording_play = false;
  int play_recorded = 0, play_target = 0;  ///< of the running request
  RgbImage play_image;                     ///< the latest play sample's camera image
  uint64_t play_image_frame = 0;
  std::vector<float> play_reading;  ///< and its beacon reading

  /// While training runs, its live progress; otherwise the models saved in the session.
  std::vector<TrainingView> training;
  bool training_running = false;
  bool training_cancelling = false;  ///< Cancel was pressed; the trainers stop at their next step
  /// A training the studio's closing (or a crash) cut short, as the session remembers it, in
  /// words (studio/training_mark.h); "" when none was.
  std::string training_cut_short;
  std::vector<RolloutView> rollouts;
  /// A real cell's trials: the one under way, the judged ones, and one played back.
  TrialView trial;
  std::vector<RealTrialsView> real_trials;
  ProbeView probe;
  SaliencyMode saliency = SaliencyMode::kOff;  ///< over the rollout and trial playbacks
  TrialPlaybackView trial_playback;
  EpisodePlaybackView episode_playback;
  bool rollouts_running = false;
  bool rollouts_cancelling = false;  ///< Cancel was pressed; the rollouts stop at their next step
  int rollout_steps_done = 0, rollout_steps_total = 0;  ///< of the running rollouts, all methods
  int rollout_tests = 10;  ///< scenes per rollout run (recon-studio --rollout-tests)
  /// How long each rollout (and real trial) runs, seconds, and why (cli::SessionRolloutSteps):
  /// the world's episode or 1.5 times the longest kept take, with a word when capped.
  double rollout_limit_s = 0, longest_take_s = 0;
  std::string rollout_limit_note;
  bool rollouts_playing = false;  ///< the playback advances by itself (10 steps a second)

  std::string report_path;  ///< empty until a report was written

  /// What runs now and holds the session ("training", "the rollouts", "a recording", ...), empty
  /// when nothing does: what a disabled control names when it says why.
  std::string busy_with;
  std::string status;  ///< one line at the bottom: what is happening
  /// The window's close button was pressed while something runs (busy_with): the studio asks
  /// whether to stop it and close or to keep it running. The application sets it, not the
  /// controller (the window is the application's).
  bool close_requested = false;
  std::vector<std::string> errors;  ///< shown until dismissed
};

}  // namespace recon::ui
