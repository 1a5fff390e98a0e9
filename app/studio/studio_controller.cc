#include "app/studio/studio_controller.h"

#include <mujoco/mujoco.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <future>

#include "app/cli/session_report_builder.h"
#include "app/cli/session_summary.h"
#include "app/cli/session_training.h"
#include "app/cli/session_world.h"
#include "devices/cell/sim_calibration.h"
#include "devices/render/mujoco_renderer.h"
#include "devices/tags/pinhole_camera.h"
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

/// A long activity on the job thread. The cell thread starts it, polls `state` for the snapshot
/// and, once it is done, applies its result to the session (only the cell thread changes the
/// session).
class StudioController::Jobs {
 public:
  struct State {
    std::string name;  ///< "calibration", "training", "rollouts"
    bool running = false;
    int calibration_points = 0;
    std::vector<ui::TrainingView> training;
    std::string error;
    std::function<void()> finish;  ///< run on the cell thread when the job is over
  };
  using Work = std::function<std::function<void()>(Jobs&)>;

  /// One thread for every job of the studio's life. It holds a renderer handle from start to
  /// end, so the calibration and rollout worlds it makes share one EGL context that lives as
  /// long as the thread: no context is made or dropped while other threads render (Mesa's
  /// llvmpipe has crashed on that).
  Jobs() {
    thread_ = std::thread([this] {
      const std::unique_ptr<worlds::SceneRenderer> keep = render::MujocoRendererFactory()();
      Loop();
    });
  }
  ~Jobs() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    cancel_ = true;
    wake_.notify_all();
    thread_.join();
  }
  /// Running, or finished but its result not yet applied on the cell thread (so the studio
  /// never looks idle between the two).
  bool Running() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_.running || state_.finish != nullptr || work_ != nullptr;
  }
  /// Queues `work` (UserError if a job runs). `work` gets this object to report progress and
  /// returns what to do on the cell thread afterwards.
  void Start(const std::string& name, Work work) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (state_.running || work_ != nullptr) {
      throw UserError("wait for the " + state_.name + " to finish");
    }
    cancel_ = false;
    state_ = {};
    state_.name = name;
    state_.running = true;
    work_ = std::move(work);
    wake_.notify_all();
  }
  void Cancel() { cancel_ = true; }
  const std::atomic<bool>* cancel_flag() const { return &cancel_; }
  template <typename Change>
  void Update(const Change& update) {
    std::lock_guard<std::mutex> lock(mutex_);
    update(state_);
  }
  /// A copy of the state; takes the finish action (and error) once the job is over.
  State Take() {
    std::lock_guard<std::mutex> lock(mutex_);
    State copy = state_;
    state_.finish = nullptr;
    state_.error.clear();
    return copy;
  }

 private:
  void Loop() {
    while (true) {
      Work work;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return quit_ || work_ != nullptr; });
        if (quit_) return;
        work = std::move(work_);
        work_ = nullptr;
      }
      std::function<void()> finish;
      std::string error;
      try {
        finish = work(*this);
      } catch (const std::exception& e) {
        error = e.what();
      }
      std::lock_guard<std::mutex> lock(mutex_);
      state_.running = false;
      state_.error = error;
      state_.finish = std::move(finish);
    }
  }

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  State state_;
  Work work_;
  bool quit_ = false;
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

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
    const Jobs::State job = jobs_.Take();
    if (job.finish) job.finish();
    if (!job.error.empty()) errors_.push_back(job.error);
  }

  bool Busy() const { return (recorder_ && recorder_->recording()) || jobs_.Running(); }
  /// Shown on screen until dismissed; the same error twice in a row is shown once.
  void AddError(const std::string& error) {
    if (errors_.empty() || errors_.back() != error) errors_.push_back(error);
  }
  const std::vector<std::string>& errors() const { return errors_; }

  void Publish(ui::StudioSnapshot& s) {
    const store::SessionManifest& m = session_->manifest();
    s = {};
    s.session_open = true;
    s.session_dir = session_->dir();
    s.world = m.world;
    s.cell_kind = m.cell;
    for (const store::DeviceEntry& d : m.devices) {
      s.devices.push_back({d.role, d.kind, d.detail, true, d.role == "camera" ? 30.0 : 10.0, ""});
    }
    const teach::WorkflowFacts facts = Facts();
    s.steps = teach::EvaluateWorkflow(facts);
    for (int i = 0; i < teach::kNumSteps; ++i) {
      s.can_open[i] = teach::CanOpen(facts, teach::kAllSteps[i]);
    }
    s.current_step = current_step_;
    s.next_step = teach::NextStep(facts);
    RenderView(s);
    const Jobs::State job = jobs_.Take();
    if (job.finish) job.finish();  // (the cell thread is the only caller)
    if (!job.error.empty()) errors_.push_back(job.error);
    s.calibration = CalibrationView();
    s.calibration.running = job.running && job.name == "calibration";
    s.calibration.points_collected = job.calibration_points;
    s.calibration.points_target = options_.calibration_points;
    s.recording = recorder_ && recorder_->recording();
    s.recording_samples = recorder_ ? recorder_->samples() : 0;
    s.teleop = "scripted teleop (the simulated teacher)";
    for (const store::EpisodeEntry& e : session_->demos()) {
      s.episodes.push_back({e.name, static_cast<int>(e.meta.num_samples), e.meta.teaching_seconds,
                            e.meta.succeeded, e.flags.bad, e.flags.split, e.problem});
    }
    s.play_samples = static_cast<int>(session_->PlaySamples());
    const nlohmann::json ledger = cli::TeachingLedgerJson(*session_);
    s.teacher_seconds = ledger["recon_play_total_s"].get<double>();
    s.training = job.name == "training" ? job.training : last_training_;
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
    s.rollouts_running = job.running && job.name == "rollouts";
    s.report_path = report_path_;
    s.errors = errors_;
    s.status = job.running ? "Running " + job.name + "..." : status_;
  }

 private:
  teach::WorkflowFacts Facts() const {
    const store::SessionManifest& m = session_->manifest();
    teach::WorkflowFacts f;
    f.session_open = true;
    f.cell_connected = true;  // simulated devices are always there
    f.beacons_required = static_cast<int>(m.beacons.size());
    f.beacons_assigned = static_cast<int>(m.beacon_assignments.size());
    for (const BeaconSpec& b : m.beacons) {
      if (!m.beacon_assignments.count(b.name)) f.unmarked_objects.push_back(b.object);
    }
    if (!m.calibration_file.empty()) {
      f.calibration_present = true;
      const calib::CalibrationReport cal =
          calib::LoadCalibration((fs::path(session_->dir()) / m.calibration_file).string());
      f.calibration_passed = cal.passed;
      f.calibration_rmse_m = cal.rmse_m;
    }
    for (const store::EpisodeEntry& e : session_->demos()) {
      if (e.flags.bad || !e.problem.empty()) continue;
      ++f.demos;
      f.demo_seconds += e.meta.teaching_seconds;
    }
    f.play_samples = static_cast<int>(session_->PlaySamples());
    f.recording_demos = recorder_ && recorder_->recording();
    f.training = jobs_.Running();
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

  ui::CalibrationView CalibrationView() const {
    ui::CalibrationView view;
    const store::SessionManifest& m = session_->manifest();
    if (m.calibration_file.empty()) return view;
    const calib::CalibrationReport cal =
        calib::LoadCalibration((fs::path(session_->dir()) / m.calibration_file).string());
    view.present = true;
    view.passed = cal.passed;
    view.rmse_m = cal.rmse_m;
    view.p95_m = cal.p95_m;
    view.threshold_m = cal.options.pass_rmse_m;
    view.residual_m = cal.residual_norm_m;
    for (bool outlier : cal.outlier) view.inlier.push_back(!outlier);
    return view;
  }

  /// The live camera, the objects one can click and where the beacons read.
  void RenderView(ui::StudioSnapshot& s) {
    auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get());
    if (tabletop == nullptr) return;  // the other worlds have no camera
    worlds::MujocoModel& scene = tabletop->scene();
    s.camera = view_->Render(scene, "top", options_.view_width, options_.view_height);
    s.camera_frame = ++camera_frames_;
    const int id = mj_name2id(scene.model(), mjOBJ_CAMERA, "top");
    const double* pos = scene.data()->cam_xpos + 3 * id;
    const double* mat = scene.data()->cam_xmat + 9 * id;
    Eigen::Matrix3d rotation;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) rotation(r, c) = mat[3 * r + c];
    }
    const tags::PinholeCamera camera = tags::PinholeCamera::FromMujoco(
        scene.model()->cam_fovy[id], options_.view_width, options_.view_height,
        Eigen::Vector3d(pos[0], pos[1], pos[2]), rotation);
    const auto pixel = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d px = camera.Project(p);
      return std::array<float, 2>{static_cast<float>(px.x()), static_cast<float>(px.y())};
    };
    const auto object = [&](const std::string& name, const Eigen::Vector3d& p) {
      const std::array<float, 2> px = pixel(p);
      s.objects.push_back({name, px[0], px[1]});
    };
    object("plate", tabletop->PlatePosition());
    object("bowl", tabletop->BowlPosition());
    object("toast", tabletop->ToastPosition());
    const store::SessionManifest& m = session_->manifest();
    const std::vector<float> reading = world_->BeaconReading();
    for (const BeaconSpec& b : m.beacons) {
      ui::BeaconView view;
      view.name = b.name;
      auto it = m.beacon_assignments.find(b.name);
      view.object = it == m.beacon_assignments.end() ? "" : it->second;
      view.quantity = b.quantity;
      view.unit = b.unit;
      view.reading = reading;
      view.pixel = pixel(tabletop->BeaconPosition());
      view.rate_hz = 1.0 / world_->StepSeconds();
      view.noise_m = m.beacon_noise_sigma;
      s.beacons.push_back(view);
    }
  }

  void Commit() {
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
    jobs_.Start("calibration", [this, seed, points, dir](Jobs& jobs) -> std::function<void()> {
      cell::SimCalibrationOptions calibration;
      calibration.seed = seed;
      calibration.points = points;
      const cell::SimCalibrationResult result =
          cell::RunSimulatedCalibration(calibration, [&](int done, int) {
            jobs.Update([&](Jobs::State& state) { state.calibration_points = done; });
          });
      const std::string path = (fs::path(dir) / "calibration.new.json").string();
      calib::SaveCalibration(result.report, path);
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
    jobs_.Start("training", [this, training, methods](Jobs& jobs) -> std::function<void()> {
      jobs.Update([&](Jobs::State& state) {
        for (const std::string& method : methods) {
          ui::TrainingView view;
          view.method = method;
          view.label = method == teach::kBaselineMethod ? "Baseline" : "RECON";
          view.steps = training.steps;
          state.training.push_back(view);
        }
      });
      for (size_t i = 0; i < methods.size(); ++i) {
        const auto start = Clock::now();
        cli::TrainSessionMethod(
            *session_, methods[i], training,
            [&](const cli::TrainingProgress& p) {
              jobs.Update([&](Jobs::State& state) {
                ui::TrainingView& view = state.training[i];
                view.label = p.label;
                view.running = true;
                view.step = p.step;
                view.seconds = std::chrono::duration<double>(Clock::now() - start).count();
                view.loss_step.push_back(static_cast<float>(p.step));
                view.action_loss.push_back(p.latest.action_loss);
                if (methods[i] == teach::kReconMethod) {
                  view.beacon_loss.push_back(p.latest.beacon_loss);
                }
                view.total_loss.push_back(p.latest.total_loss);
              });
            },
            jobs.cancel_flag());
        jobs.Update([&](Jobs::State& state) {
          state.training[i].running = false;
          state.training[i].done = true;
        });
      }
      std::vector<ui::TrainingView> finished;
      jobs.Update([&](Jobs::State& state) { finished = state.training; });
      return [this, finished] {
        last_training_ = finished;
        status_ = "Trained.";
      };
    });
  }
  void Apply(const ui::CancelTraining&) { jobs_.Cancel(); }
  void Apply(const ui::RunRollouts& c) {
    RequireIdle("roll out");
    const int tests = c.tests > 0 ? c.tests : options_.rollout_tests;
    jobs_.Start("rollouts", [this, tests](Jobs&) -> std::function<void()> {
      for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
        if (fs::exists(fs::path(session_->dir()) / "checkpoints" /
                       (std::string(method) + ".ckpt"))) {
          cli::EvaluateSessionMethod(*session_, method, tests, cli::DefaultTestSeed(*session_));
        }
      }
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
  Jobs jobs_;
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
