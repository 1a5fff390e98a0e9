#include "engine/teach/recorder.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/teach/play_recorder.h"

namespace recon::teach {

namespace {

// The stream of a take's injected action noise (Rng::Derive of its scenario seed).
constexpr uint64_t kNoiseStream = 0xDA27;

// The scene of a session's take number `number`: in worlds with n > 1 demonstrations per
// configuration, configuration number / n, drawn from the scenario seed of its first take;
// elsewhere none (configuration -1: the take's own scenario).
struct SessionScene {
  int configuration = -1;
  uint64_t configuration_seed = 0;
};

SessionScene SessionSceneOf(const worlds::World& world, uint64_t session_seed, int number) {
  const int n = world.DemosPerConfiguration();
  if (n <= 1) return {};
  const int configuration = number / n;
  return {configuration, store::Session::ScenarioSeed(session_seed, configuration * n, false)};
}

}  // namespace

void StartSessionDemo(DemoRecorder& recorder, const worlds::World& world, uint64_t session_seed,
                      int number) {
  const uint64_t seed = store::Session::ScenarioSeed(session_seed, number, false);
  const SessionScene scene = SessionSceneOf(world, session_seed, number);
  if (scene.configuration < 0) {
    recorder.Start(seed);
  } else {
    recorder.StartTake(seed, scene.configuration_seed, scene.configuration);
  }
}

void ShowSessionDemoScene(worlds::World& world, uint64_t session_seed, int number) {
  const uint64_t seed = store::Session::ScenarioSeed(session_seed, number, false);
  const SessionScene scene = SessionSceneOf(world, session_seed, number);
  if (scene.configuration < 0) {
    world.Reset(seed);
  } else {
    world.ResetTake(seed, scene.configuration_seed, scene.configuration);
  }
}

void StartSessionPlay(PlayRecorder& recorder, const worlds::World& world, uint64_t session_seed,
                      int number, int count) {
  const uint64_t seed = store::Session::ScenarioSeed(session_seed, number, true);
  const SessionScene scene = SessionSceneOf(world, session_seed, number);
  if (scene.configuration < 0) {
    recorder.Start(seed, count);
  } else {
    recorder.StartTake(seed, scene.configuration_seed, scene.configuration, count);
  }
}

store::PlayRecord RecordSessionPlayChunk(worlds::World& world, uint64_t session_seed, int number,
                                         int count) {
  PlayRecorder recorder(world, "simulated-play");
  StartSessionPlay(recorder, world, session_seed, number, count);
  while (recorder.Tick()) {
  }
  return recorder.Take();
}

void StartSessionTake(DemoRecorder& recorder, const worlds::World& world,
                      const store::SessionManifest& manifest, int number, uint64_t seed) {
  recorder.SetActionNoise(manifest.demo_noise_sigma);
  if (store::Session::ScenarioSeed(manifest.seed, number, false) == seed) {
    StartSessionDemo(recorder, world, manifest.seed, number);
  } else {
    recorder.Start(seed);
  }
}

TeacherAction ScriptedTeacher(const worlds::World& world) { return {world.ExpertAction(), false}; }

DemoRecorder::DemoRecorder(worlds::World& world, Teacher teacher, std::string source, TakeEnd end)
    : world_(world), teacher_(std::move(teacher)), source_(std::move(source)), end_(end) {}

void DemoRecorder::Start(uint64_t seed) { StartTake(seed, seed, -1); }

void DemoRecorder::SetActionNoise(double sigma) {
  if (!std::isfinite(sigma) || sigma < 0) {
    throw UserError("demonstration noise must be a non-negative number (got " +
                    FormatNumber(sigma) + ")");
  }
  noise_sigma_ = sigma;
}

void DemoRecorder::StartTake(uint64_t seed, uint64_t configuration_seed, int configuration) {
  if (configuration < 0) {
    world_.Reset(seed);
  } else {
    world_.ResetTake(seed, configuration_seed, configuration);
  }
  noise_rng_.Seed(Rng::Derive(seed, kNoiseStream));
  record_ = {};
  record_.meta.kind = "demo";
  record_.meta.seed = seed;
  record_.meta.source = source_;
  record_.meta.recorded_at = store::NowIso8601();
  record_.episode.samples.reserve(world_.EpisodeLength());
  recording_ = true;
}

bool DemoRecorder::Tick() {
  if (!recording_) return false;
  worlds::Observation obs = world_.Observe();
  Sample sample;
  sample.x = std::move(obs.x);
  sample.y = std::move(obs.y);
  sample.b = world_.BeaconReading();
  TeacherAction action = teacher_(world_);
  sample.u = std::move(action.u);
  world_.Step(worlds::PerturbAction(world_, sample.u, noise_sigma_, noise_rng_));
  record_.episode.samples.push_back(std::move(sample));
  // robomimic's sparse reward: 1 once the task is done.
  record_.rewards.push_back(world_.TaskSucceeded() ? 1.0 : 0.0);
  // A teacher stops recording once the task is done, or says so.
  const bool done =
      end_ == TakeEnd::kPerson ? world_.GoalHoldsAndClear() : world_.DemonstrationDone();
  if (action.finished || done || samples() >= world_.EpisodeLength()) {
    recording_ = false;
  }
  return recording_;
}

store::DemoRecord DemoRecorder::Take() {
  recording_ = false;
  record_.meta.num_samples = samples();
  record_.meta.teaching_seconds = samples() * world_.StepSeconds();
  record_.meta.succeeded = world_.HasSuccess() && world_.TaskSucceeded();
  return std::move(record_);
}

namespace {

void RecordEpisodes(store::Session& session, worlds::World& world, const RecordPlan& plan,
                    const std::function<void(const RecordProgress&)>& on_commit,
                    const std::function<bool()>& cancelled) {
  RecordProgress progress;
  DemoRecorder recorder(world, ScriptedTeacher, "scripted-teleop");
  recorder.SetActionNoise(session.manifest().demo_noise_sigma);
  for (int i = 0; i < plan.demos && !cancelled(); ++i) {
    StartSessionDemo(recorder, world, plan.seed, session.NextDemoNumber());
    while (recorder.Tick()) {
    }
    const store::EpisodeEntry& entry = session.CommitDemo(recorder.Take());
    ++progress.demos_done;
    progress.last_committed =
        entry.name + " (" + std::to_string(entry.meta.num_samples) + " samples" +
        (world.HasSuccess() ? (entry.meta.succeeded ? ", done" : ", not done") : "") + ")";
    if (on_commit) on_commit(progress);
  }
  while (progress.play_samples_done < plan.play_samples && !cancelled()) {
    const int chunk_size = std::min(std::max(1, world.PlaySamplesPerScenario()),
                                    plan.play_samples - progress.play_samples_done);
    const store::EpisodeEntry& entry = session.CommitPlay(
        RecordSessionPlayChunk(world, plan.seed, session.NextPlayNumber(), chunk_size));
    progress.play_samples_done += static_cast<int>(entry.meta.num_samples);
    progress.last_committed =
        entry.name + " (" + std::to_string(entry.meta.num_samples) + " play samples)";
    if (on_commit) on_commit(progress);
  }
}

}  // namespace

void RecordIntoSession(store::Session& session, worlds::World& world, const RecordPlan& plan,
                       const std::function<void(const RecordProgress&)>& on_commit,
                       const std::atomic<bool>* cancel) {
  if (plan.demos < 0 || plan.play_samples < 0) {
    throw UserError("the numbers of demonstrations and play samples must not be negative");
  }
  if (!(world.Spec() == session.manifest().spec)) {
    throw UserError("the world records " + world.Spec().ToString() + " but session " +
                    session.dir() + " holds " + session.manifest().spec.ToString());
  }
  const auto cancelled = [&] { return cancel != nullptr && cancel->load(); };
  // One index rebuild for the whole run instead of one per episode (Session::DeferIndex); on an
  // error the index is still brought up to date with what was committed.
  session.DeferIndex(true);
  try {
    RecordEpisodes(session, world, plan, on_commit, cancelled);
  } catch (...) {
    session.DeferIndex(false);
    throw;
  }
  session.DeferIndex(false);
}

const store::EpisodeEntry& ReRecordDemo(store::Session& session, worlds::World& world,
                                        const std::string& name) {
  const store::EpisodeEntry& old = session.Find(name);
  if (old.name.rfind("demo_", 0) != 0) throw UserError(name + " is not a demonstration");
  if (!old.problem.empty() && old.meta.seed == 0) {
    throw UserError(name +
                    " cannot be re-recorded: its file is damaged and its scenario seed "
                    "unknown (" +
                    old.problem + ")");
  }
  DemoRecorder recorder(world, ScriptedTeacher, "scripted-teleop");
  StartSessionTake(recorder, world, session.manifest(), old.number, old.meta.seed);
  while (recorder.Tick()) {
  }
  return session.CommitDemo(recorder.Take(), name);
}

}  // namespace recon::teach
