// StudioCell's trials on a real arm: the protocol a lab runs a trained policy by (StartTrials):
// the next test layout is shown, the teacher sets it up and runs the trial, the arm returns to
// its home pose (where every demonstration began), the policy drives it through the safety
// envelope until its time is up or the teacher stops it, the teacher judges it, and the trial
// (with the frames the policy saw) is kept before the next one starts.

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "app/cli/result_staleness.h"
#include "app/cli/session_training.h"
#include "app/cli/session_world.h"
#include "app/studio/cell_view.h"
#include "app/studio/studio_cell.h"
#include "app/studio/trial_run.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/learn/learner.h"
#include "engine/store/episode_file.h"
#include "engine/store/real_trials.h"
#include "engine/store/rollout_summary.h"
#include "engine/store/training_record.h"
#include "engine/teach/homing.h"
#include "engine/teach/workflow.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::studio {

namespace fs = std::filesystem;

namespace {

/// The cell the trials ran on, for their log: its devices as a session's manifest describes them
/// ("camera: ..., arm: ..."), whichever cell the session itself was taught in.
std::string TrialCell(const CellSource& source) {
  store::SessionManifest described;
  source.DescribeInto(described);
  std::string cell = described.cell;
  std::string devices;
  for (const store::DeviceEntry& d : described.devices) {
    if (d.role == "teleop") continue;
    devices += (devices.empty() ? "" : ", ") + d.role + ": " + d.kind +
               (d.detail.empty() ? "" : " " + d.detail);
  }
  return devices.empty() ? cell : cell + " (" + devices + ")";
}

/// The seed trial n's scene derives from (as the n-th simulated rollout's scene does): the
/// seed of the session's simulated rollouts, this method's first, so each trial is a scene
/// that was also rolled out in simulation; the session's default test seed when it has none.
uint64_t TrialTestSeed(const store::Session& session, const std::string& method) {
  const std::map<std::string, store::RolloutSummary> simulated =
      store::ReadRolloutSummaries(session);
  if (const auto own = simulated.find(method); own != simulated.end()) return own->second.seed;
  if (!simulated.empty()) return simulated.begin()->second.seed;
  return cli::DefaultTestSeed(session);
}

}  // namespace

void StudioCell::Apply(const ui::StartTrials& c) {
  RequireIdle("start trials");
  RequireNoEmergencyStop("start trials");
  if (!source_->RunsTrials()) {
    throw UserError(
        "trials run on a real arm: open the session with --cell PROFILE; in the simulated cell, "
        "run rollouts");
  }
  if (c.method != teach::kBaselineMethod && c.method != teach::kReconMethod) {
    throw UserError("unknown method \"" + c.method + "\" (valid: baseline, recon)");
  }
  const int count = c.trials > 0 ? c.trials : options_.rollout_tests;
  const std::string checkpoint = session_->CheckpointPath(c.method);
  if (!fs::exists(checkpoint)) {
    throw UserError("train " + c.method + " first: there is no " + checkpoint);
  }
  auto run = std::make_unique<TrialRun>();
  run->method = c.method;
  const std::optional<store::TrainingRecord> trained =
      store::ReadTrainingRecord(*session_, c.method);
  run->label = trained ? trained->label : c.method;
  run->model_id = cli::CheckpointModelId(checkpoint);
  run->policy = learn::LoadPolicy(checkpoint);
  run->test_seed = TrialTestSeed(*session_, c.method);
  const std::optional<store::RealTrialLog> log = store::ReadRealTrialLog(*session_, c.method);
  run->first = (log ? static_cast<int>(log->trials.size()) : 0) + 1;
  run->last = run->first + count - 1;
  const int first = run->first;
  trial_ = std::move(run);
  try {
    SetUpTrial(first);
  } catch (...) {
    trial_.reset();  // no trial shown half set up
    throw;
  }
}

void StudioCell::SetUpTrial(int number) {
  TrialRun& run = *trial_;
  run.number = number;
  run.phase = ui::TrialPhase::kSetUp;
  run.step = 0;
  run.stopped = false;
  run.frames = {};
  run.frames.image_size = session_->manifest().image_size;
  // Trial n sets up the n-th scene of the simulated rollouts' test plan, so the two compare.
  run.scene_seed = Rng::Derive(run.test_seed, static_cast<uint64_t>(number - 1));
  const std::unique_ptr<worlds::World> plan =
      cli::MakeSimulatedTaskWorld(session_->manifest(), "none");
  plan->Reset(run.scene_seed);
  run.layout = plan->ObjectLayout();
  status_ = "Trial " + std::to_string(number) + " of " + run.label +
            ": set the objects up as shown, then run it.";
}

void StudioCell::Apply(const ui::RunTrial&) {
  if (!trial_ || trial_->phase != ui::TrialPhase::kSetUp) {
    throw UserError("no trial is waiting to run: start trials first");
  }
  RequireNoEmergencyStop("run a trial");
  TrialRun& run = *trial_;
  run.phase = ui::TrialPhase::kCountdown;
  run.message.clear();
  // As before a person's take: the teacher steps back from the table first.
  run.starts = Now() + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(options_.countdown_s));
  status_ = "Trial " + std::to_string(run.number) +
            ": after the countdown the arm returns home, then the policy runs.";
}

void StudioCell::Apply(const ui::StopTrial&) {
  if (!trial_) throw UserError("no trial runs");
  TrialRun& run = *trial_;
  if (run.phase == ui::TrialPhase::kCountdown || run.phase == ui::TrialPhase::kHoming) {
    if (run.phase == ui::TrialPhase::kHoming) HoldArm();
    run.phase = ui::TrialPhase::kSetUp;  // the policy never ran: the same trial waits again
    status_ = "Trial " + std::to_string(run.number) + " not started.";
  } else if (run.phase == ui::TrialPhase::kRunning) {
    HoldArm();
    run.stopped = true;
    run.phase = ui::TrialPhase::kJudge;
    status_ = "Trial " + std::to_string(run.number) + " stopped after " + std::to_string(run.step) +
              " steps: judge it.";
  }
}

void StudioCell::Apply(const ui::JudgeTrial& c) {
  if (!trial_ || trial_->phase != ui::TrialPhase::kJudge) {
    throw UserError("no trial waits for a verdict");
  }
  TrialRun& run = *trial_;
  store::RealTrial trial;
  trial.number = run.number;
  trial.scene_seed = run.scene_seed;
  trial.layout = run.layout;
  trial.succeeded = c.succeeded;
  trial.reason = c.reason;
  trial.stopped = run.stopped;
  trial.steps = run.step;
  trial.seconds = run.step * world_->StepSeconds();
  trial.judged_at = store::NowIso8601();
  store::RealTrialLog log =
      store::ReadRealTrialLog(*session_, run.method).value_or(store::RealTrialLog{});
  log.method = run.method;
  log.label = run.label;
  log.model_id = run.model_id;
  log.cell = TrialCell(*source_);
  if (static_cast<int>(log.trials.size()) + 1 != run.number) {
    throw UserError("the session's " + run.method + " trials changed while this one ran (" +
                    std::to_string(log.trials.size()) + " judged now): start trials again");
  }
  // The frames first: once the log names them, they are there.
  if (!run.frames.y.empty()) {
    store::WriteTrialFrames(session_->TrialFramesPath(run.method, run.number), run.frames);
    trial.frames = store::Session::TrialFramesRelativePath(run.method, run.number);
  }
  log.trials.push_back(trial);
  store::WriteRealTrialLog(session_->RealTrialsPath(run.method), log);
  Changed();
  status_ = "Trial " + std::to_string(run.number) + (c.succeeded ? " succeeded" : " failed") +
            " (" + std::to_string(log.successes()) + " of " + std::to_string(log.trials.size()) +
            " so far).";
  if (run.number < run.last) {
    SetUpTrial(run.number + 1);
  } else {
    trial_.reset();
    status_ += " Trials done.";
  }
}

void StudioCell::Apply(const ui::EndTrials&) {
  if (!trial_) return;
  if (trial_->phase == ui::TrialPhase::kRunning) HoldArm();
  trial_.reset();
  status_ = "Trials ended; the judged ones are in the session.";
}

void StudioCell::AbortTrial(const std::string& why) {
  if (!trial_) return;
  TrialRun& run = *trial_;
  if (!TrialMoving()) return;
  HoldArm();
  run.message = "Trial " + std::to_string(run.number) + " stopped after " +
                std::to_string(run.step) + " steps: " + why +
                ". The arm is stopped and the trial was not kept: set the layout up again and "
                "run it once the cause is fixed.";
  run.phase = ui::TrialPhase::kSetUp;
  run.step = 0;
  run.frames = {};
  run.frames.image_size = session_->manifest().image_size;
  AddError(run.message);
}

void StudioCell::HoldArm() {
  try {
    world_->Reset(0);  // a real cell's Reset stops the arm where it is
  } catch (const std::exception&) {
    // The arm is gone: its controller stopped it when the commands stopped.
  }
}

void StudioCell::TickTrial(Clock::time_point now) {
  TrialRun& run = *trial_;
  if (run.phase == ui::TrialPhase::kCountdown) {
    if (now < run.starts) return;
    run.phase = ui::TrialPhase::kHoming;
    run.starts = now;
    run.homing_from_rad = 0;
    run.homing_progress = 0;
    status_ = "Trial " + std::to_string(run.number) + ": the arm returns to its home pose.";
  }
  if (run.phase == ui::TrialPhase::kHoming) {
    if (now < next_tick_) return;
    next_tick_ = now + kControlPeriod;
    StepHoming(now);
    return;
  }
  if (run.phase != ui::TrialPhase::kRunning || now < next_tick_) return;
  next_tick_ = now + kControlPeriod;
  try {
    worlds::Observation obs = world_->Observe();
    std::vector<float> u;
    if (run.ensembler) {
      u = run.ensembler->Step(run.policy.ActChunkBatch({obs.x}, {obs.y}).front());
    } else {
      u = run.policy.Act(obs.x, obs.y);
    }
    world_->Step(u);
    arm_health_.Add(Seconds(now));
    run.frames.x.push_back(std::move(obs.x));
    run.frames.y.push_back(std::move(obs.y));
    run.frames.u.push_back(std::move(u));
    ++run.step;
  } catch (const UserError& e) {
    AbortTrial(e.what());
    return;
  }
  if (run.step >= cli::SessionRolloutSteps(*session_, *world_)) {
    HoldArm();
    run.phase = ui::TrialPhase::kJudge;
    status_ = "Trial " + std::to_string(run.number) + " ran its " + std::to_string(run.step) +
              " steps: judge it.";
  }
}

void StudioCell::StepHoming(Clock::time_point now) {
  TrialRun& run = *trial_;
  const safety::GuardedArm* arm = source_->GuardedArmOf(world_.get());
  try {
    if (arm == nullptr) throw UserError("the cell has no arm");
    const std::array<double, 6> q = arm->State().position_rad;
    const double left = teach::HomingDistance(q, worlds::Ur5Arm::kHome);
    run.homing_from_rad = std::max(run.homing_from_rad, left);
    run.homing_progress =
        run.homing_from_rad > 0 ? static_cast<float>(1.0 - left / run.homing_from_rad) : 1.0f;
    if (StepTowardHome(q, run.starts, now)) StartPolicy();
  } catch (const UserError& e) {
    AbortTrial(std::string("while returning home, ") + e.what());
  }
}

void StudioCell::StartPolicy() {
  TrialRun& run = *trial_;
  HoldArm();
  run.phase = ui::TrialPhase::kRunning;
  run.homing_progress = 1;
  run.ensembler.reset();
  if (run.policy.action_chunk() > 1) {
    run.ensembler.emplace(run.policy.action_chunk(), run.policy.spec().u_dim, 0.01,
                          run.policy.ensembled_actions());
  }
  status_ = "Trial " + std::to_string(run.number) + " running: Stop (or the e-stop) halts it.";
}

bool StudioCell::TrialMoving() const {
  return trial_ &&
         (trial_->phase == ui::TrialPhase::kCountdown || trial_->phase == ui::TrialPhase::kHoming ||
          trial_->phase == ui::TrialPhase::kRunning);
}

void StudioCell::ShowTrial(ui::StudioSnapshot& s) const {
  if (!trial_) return;
  const TrialRun& run = *trial_;
  ui::TrialView& v = s.trial;
  v.phase = run.phase;
  v.method = run.method;
  v.label = run.label;
  v.number = run.number;
  v.first = run.first;
  v.last = run.last;
  v.scene_seed = run.scene_seed;
  for (const auto& [name, xy] : run.layout) {
    ui::TrialView::Object o;
    o.name = name;
    o.table_m = {static_cast<float>(xy[0]), static_cast<float>(xy[1])};
    o.pixel = source_->TablePixel({xy[0], xy[1], 0.0});
    v.layout.push_back(o);
  }
  if (run.phase == ui::TrialPhase::kCountdown) {
    v.countdown_s = std::max(0.0, std::chrono::duration<double>(run.starts - Now()).count());
  }
  v.homing_progress = run.homing_progress;
  v.step = run.step;
  v.max_steps = cli::SessionRolloutSteps(*session_, *world_);
  v.stopped = run.stopped;
  v.message = run.message;
}

void StudioCell::Apply(const ui::ShowTrialFrame& c) {
  const std::optional<store::RealTrialLog> log = store::ReadRealTrialLog(*session_, c.method);
  if (!log || c.number < 1 || c.number > static_cast<int>(log->trials.size())) {
    throw UserError("no trial " + std::to_string(c.number) + " of " + c.method + " to play back");
  }
  const store::RealTrial& trial = log->trials[static_cast<size_t>(c.number - 1)];
  if (!trial.frames) throw UserError("trial " + std::to_string(c.number) + " kept no frames");
  if (trial_playback_.method != c.method || trial_playback_.number != c.number) {
    trial_frames_ = store::ReadTrialFrames((fs::path(session_->dir()) / *trial.frames).string());
    trial_playback_.method = c.method;
    trial_playback_.number = c.number;
  }
  trial_playback_.frames = static_cast<int>(trial_frames_.y.size());
  trial_playback_.frame = std::clamp(c.frame, 0, std::max(0, trial_playback_.frames - 1));
  if (trial_playback_.frames > 0) DrawTrialFrame();
}

}  // namespace recon::studio
