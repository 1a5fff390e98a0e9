#include "app/studio/studio_controller.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <optional>

#include "app/cli/session_report_builder.h"
#include "app/cli/session_summary.h"
#include "app/cli/session_training.h"
#include "app/cli/session_world.h"
#include "app/studio/cell_view.h"
#include "app/studio/job_thread.h"
#include "app/studio/studio_jobs.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/store/session.h"
#include "engine/teach/recorder.h"
#include "engine/teach/session_setup.h"
#include "engine/teach/workflow.h"
#include "engine/worlds/tabletop.h"

namespace recon::studio {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Everything the cell thread owns: the session, the simulated world, its camera, the recorder.
class StudioController::Cell {
 public:
  explicit Cell(const StudioOptions& options) : options_(options) {}

  /// Opens or creates the session and the world. Runs on the cell thread (GL contexts and
  /// MuJoCo data belong to the thread that made them).
  void Start() {
    const std::string world =
        store::Session::Exists(options_.session_dir)
            ? store::LoadManifest((fs::path(options_.session_dir) / "session.json").string()).world
            : options_.world;
    // The steps (a camera to click objects in, a UWB frame to calibrate) are the arm cell's.
    if (world != "tabletop") {
      throw UserError("the studio teaches in the tabletop cell; a " + world +
                      " session is recorded and trained from the command line (recon record, "
                      "recon train)");
    }
    if (store::Session::Exists(options_.session_dir)) {
      session_.emplace(store::Session::Open(options_.session_dir));
      world_ = cli::MakeSessionWorld(session_->manifest(), session_->manifest().placement);
    } else {
      store::SessionManifest probe;
      probe.world = options_.world;
      probe.placement = teach::DefaultTeachingPlacement(options_.world);
      probe.image_size = options_.image_size;
      world_ = cli::MakeSessionWorld(probe, probe.placement);
      teach::SessionSetup setup;
      setup.world_name = probe.world;
      setup.placement = probe.placement;
      setup.image_size = probe.image_size;
      setup.seed = options_.seed;
      session_.emplace(
          store::Session::Create(options_.session_dir, teach::NewSessionManifest(setup, *world_)));
    }
    world_->Reset(
        store::Session::ScenarioSeed(session_->manifest().seed, session_->NextDemoNumber(), false));
    view_ = render::MujocoRendererFactory()();
    status_ = "Session " + options_.session_dir + ": " + session_->manifest().world + ", " +
              session_->manifest().cell + " cell.";
  }

  void Handle(const ui::StudioCommand& command) {
    Changed();  // whatever it does (or fails to do), the workflow is re-read
    std::visit([this](const auto& c) { Apply(c); }, command);
  }

  /// One pass of the cell loop: a recording step, the camera, a finished job.
  void Tick() {
    if (recorder_ && recorder_->recording()) {
      if (!options_.real_time || Clock::now() >= next_tick_) {
        next_tick_ = Clock::now() + std::chrono::milliseconds(100);
        recorder_->Tick();
        if (!recorder_->recording()) Commit();
      }
    }
    ApplyFinishedJob();
  }

  bool Busy() const { return (recorder_ && recorder_->recording()) || jobs_.Running(); }
  /// Shown on screen until dismissed; the same error twice in a row is shown once.
  void AddError(const std::string& error) {
    if (errors_.empty() || errors_.back() != error) errors_.push_back(error);
  }
  const std::vector<std::string>& errors() const { return errors_; }

  /// The snapshot: the session's side (rebuilt only after something changed it, see dirty_),
  /// then what moves by itself: the camera, the recording, the job's progress.
  void Publish(ui::StudioSnapshot& s) {
    if (dirty_) {
      RebuildSessionView();
      dirty_ = false;
    }
    s = session_view_;
    s.current_step = current_step_;
    RenderView(s);
    const JobState job = jobs_.Peek();
    s.calibration.running = job.running && job.name == "calibration";
    s.calibration.points_collected = job.calibration_points;
    s.recording = recorder_ && recorder_->recording();
    s.recording_samples = recorder_ ? recorder_->samples() : 0;
    s.training = job.name == "training" ? job.training : last_training_;
    s.rollouts_running = job.running && job.name == "rollouts";
    s.report_path = report_path_;
    s.errors = errors_;
    s.status = job.running ? "Running " + job.name + "..." : status_;
  }

 private:
  /// Marks the session's side of the snapshot stale: after every command, commit and job.
  void Changed() { dirty_ = true; }

  void ApplyFinishedJob() {
    const JobState job = jobs_.Take();
    if (job.finish) job.finish();
    if (!job.error.empty()) AddError(job.error);
    if (job.finish || !job.error.empty()) Changed();
  }

  /// Everything the snapshot shows of the session and the workflow. Reads the calibration and
  /// the rollout files, so it runs when something changed, not at the camera's 30 Hz.
  void RebuildSessionView() {
    const store::SessionManifest& m = session_->manifest();
    ui::StudioSnapshot& s = session_view_;
    s = {};
    s.session_open = true;
    s.session_dir = session_->dir();
    s.world = m.world;
    s.cell_kind = m.cell;
    for (const store::DeviceEntry& d : m.devices) {
      s.devices.push_back({d.role, d.kind, d.detail, true, d.role == "camera" ? 30.0 : 10.0, ""});
    }
    std::optional<calib::CalibrationReport> calibration;
    if (!m.calibration_file.empty()) {
      calibration =
          calib::LoadCalibration((fs::path(session_->dir()) / m.calibration_file).string());
    }
    const teach::WorkflowFacts facts = Facts(calibration);
    s.steps = teach::EvaluateWorkflow(facts);
    for (int i = 0; i < teach::kNumSteps; ++i) {
      s.can_open[i] = teach::CanOpen(facts, teach::kAllSteps[i]);
    }
    s.next_step = teach::NextStep(facts);
    s.calibration = CalibrationView(calibration);
    s.calibration.points_target = options_.calibration_points;
    s.teleop = "scripted teleop (the simulated teacher)";
    for (const store::EpisodeEntry& e : session_->demos()) {
      s.episodes.push_back({e.name, static_cast<int>(e.meta.num_samples), e.meta.teaching_seconds,
                            e.meta.succeeded, e.flags.bad, e.flags.split, e.problem});
    }
    s.play_samples = static_cast<int>(session_->PlaySamples());
    s.teacher_seconds = cli::TeachingLedgerJson(*session_)["recon_play_total_s"].get<double>();
    for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
      const auto r = cli::ReadJsonFile(
          (fs::path(session_->dir()) / "rollouts" / (std::string(method) + ".json")).string());
      if (!r) continue;
      ui::RolloutView view;
      view.method = method;
      view.label = r->value("label", std::string(method));
      view.metric_name = r->value("metric_name", std::string());
      view.metric_mean = r->value("metric_mean", 0.0);
      view.metric_sem = r->value("metric_sem", 0.0);
      view.has_success = r->value("has_success", false);
      view.success_rate = r->value("success_rate", 0.0);
      view.tests = r->value("tests", 0);
      s.rollouts.push_back(view);
    }
  }

  teach::WorkflowFacts Facts(const std::optional<calib::CalibrationReport>& calibration) const {
    const store::SessionManifest& m = session_->manifest();
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
    for (const store::EpisodeEntry& e : session_->demos()) {
      if (e.flags.bad || !e.problem.empty()) continue;
      ++f.demos;
      f.demo_seconds += e.meta.teaching_seconds;
    }
    f.play_samples = static_cast<int>(session_->PlaySamples());
    f.recording_demos = recorder_ && recorder_->recording();
    f.training = jobs_.RunningName() == "training";
    for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
      const fs::path dir(session_->dir());
      if (fs::exists(dir / "checkpoints" / (std::string(method) + ".ckpt"))) {
        f.trained_methods.push_back(method);
      }
      if (fs::exists(dir / "rollouts" / (std::string(method) + ".json"))) {
        f.evaluated_methods.push_back(method);
      }
    }
    f.report_written = fs::exists(fs::path(session_->dir()) / "report" / "report.html");
    return f;
  }

  static ui::CalibrationView CalibrationView(
      const std::optional<calib::CalibrationReport>& calibration) {
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

  /// The live camera, the objects one can click and where the beacons read.
  void RenderView(ui::StudioSnapshot& s) {
    auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get());
    if (tabletop == nullptr) return;  // the other worlds have no camera
    ShowTabletopView(*tabletop, *view_, options_.view_width, options_.view_height,
                     session_->manifest(), world_->BeaconReading(), s);
    s.camera_frame = ++camera_frames_;
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

  void Apply(const ui::OpenStep& c) { current_step_ = c.step; }
  void Apply(const ui::AssignBeacon& c) {
    RequireIdle("assign a beacon");
    session_->AssignBeacon(c.beacon, c.object);
    status_ = "Beacon " + c.beacon + " marks the " + c.object + ".";
  }
  void Apply(const ui::StartCalibration&) {
    RequireIdle("calibrate");
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
    recorder_ =
        std::make_unique<teach::DemoRecorder>(*world_, teach::ScriptedTeacher, "scripted-teleop");
    recorder_->Start(
        store::Session::ScenarioSeed(session_->manifest().seed, session_->NextDemoNumber(), false));
    status_ = "Recording a demonstration.";
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
    const store::EpisodeEntry& e = session_->Find(c.name);
    recorder_ =
        std::make_unique<teach::DemoRecorder>(*world_, teach::ScriptedTeacher, "scripted-teleop");
    recorder_->Start(e.meta.seed);
    replace_ = c.name;
    status_ = "Re-recording " + c.name + ".";
  }
  void Apply(const ui::MarkEpisodeBad& c) {
    RequireIdle("mark an episode");
    session_->MarkBad(c.name, c.bad);
  }
  void Apply(const ui::RecordPlay& c) {
    RequireIdle("record play data");
    teach::RecordPlan plan;
    plan.play_samples = c.samples;
    plan.seed = session_->manifest().seed;
    teach::RecordIntoSession(*session_, *world_, plan);
    world_->Reset(
        store::Session::ScenarioSeed(session_->manifest().seed, session_->NextDemoNumber(), false));
    status_ = "Recorded " + std::to_string(c.samples) + " play samples.";
  }
  void Apply(const ui::StartTraining& c) {
    RequireIdle("train");
    cli::SessionTrainingOptions training;
    training.steps = c.steps > 0 ? std::min(c.steps, options_.train_steps) : options_.train_steps;
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
    const int tests = c.tests > 0 ? c.tests : options_.rollout_tests;
    jobs_.Start("rollouts", [this, tests](JobThread&) -> std::function<void()> {
      RollOutTrainedMethods(*session_, tests);
      return [this] { status_ = "Rollouts done."; };
    });
  }
  void Apply(const ui::ShowRolloutFrame&) {}  // frame-by-frame playback: not built yet
  void Apply(const ui::WriteReport&) {
    RequireIdle("write the report");
    report_path_ = cli::WriteReportForSession(*session_);
    status_ = "Wrote " + report_path_ + ".";
  }
  void Apply(const ui::DismissErrors&) { errors_.clear(); }

  StudioOptions options_;
  std::optional<store::Session> session_;
  std::unique_ptr<worlds::World> world_;
  std::unique_ptr<worlds::SceneRenderer> view_;
  std::unique_ptr<teach::DemoRecorder> recorder_;
  std::optional<std::string> replace_;
  Clock::time_point next_tick_ = Clock::now();
  JobThread jobs_;
  ui::StudioSnapshot session_view_;  ///< the session's side of the snapshot (RebuildSessionView)
  bool dirty_ = true;
  std::vector<ui::TrainingView> last_training_;
  teach::Step current_step_ = teach::Step::kCell;
  std::vector<std::string> errors_;
  std::string status_;
  std::string report_path_;
  uint64_t camera_frames_ = 0;
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
