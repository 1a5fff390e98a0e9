#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/store/episode_file.h"
#include "engine/store/session.h"
#include "engine/teach/play_recorder.h"
#include "engine/worlds/world.h"

namespace recon::teach {

/// What the teacher does at one control step.
struct TeacherAction {
  std::vector<float> u;   ///< the action the arm (or point) is driven with
  bool finished = false;  ///< the teacher ends the demonstration after this step
};

/// A teacher: reads the world's current state, returns an action. The simulated teacher is the
/// world's scripted expert (ScriptedTeacher); the app adapts keyboard and gamepad teleops.
using Teacher = std::function<TeacherAction(const worlds::World&)>;

/// The world's expert as a teacher: its ExpertAction, finished when DemonstrationDone().
TeacherAction ScriptedTeacher(const worlds::World& world);

/// Records one demonstration a step at a time, so a GUI can tick it from its frame loop and show
/// the live view between ticks; `recon record` ticks it in a loop. Each tick stores the sample
/// the teacher saw (x, y, beacon reading b) with the action they took, then steps the world.
class DemoRecorder {
 public:
  /// Where a take ends by itself: at the scripted teacher's end (World::DemonstrationDone) or
  /// where a person ends it (World::GoalHoldsAndClear: the goal holds, the gripper clear).
  enum class TakeEnd { kScripted, kPerson };

  /// `source` names the teacher in the episode's metadata, e.g. "scripted-teleop".
  DemoRecorder(worlds::World& world, Teacher teacher, std::string source,
               TakeEnd end = TakeEnd::kScripted);

  /// Resets the world to scenario `seed` and starts a new recording.
  void Start(uint64_t seed);
  /// Starts take `seed` of scene configuration `configuration`, whose scene comes from
  /// `configuration_seed` (World::ResetTake).
  void StartTake(uint64_t seed, uint64_t configuration_seed, int configuration);
  /// Noise injected into the executed actions from the next Start on (worlds::DemoNoise; 0 =
  /// off, the default). The stored actions stay the teacher's. UserError if negative or not
  /// finite.
  void SetActionNoise(double sigma);
  /// Records one step. Returns false once the recording is over (the teacher finished or the
  /// world's episode length was reached).
  bool Tick();
  bool recording() const { return recording_; }
  int samples() const { return static_cast<int>(record_.episode.samples.size()); }
  /// What was recorded so far.
  const Episode& episode() const { return record_.episode; }
  /// The latest recorded sample (nullptr before the first).
  const Sample* last() const {
    return record_.episode.samples.empty() ? nullptr : &record_.episode.samples.back();
  }
  /// Ends the recording here without handing it over: what was recorded so far stays, for
  /// Take() or to be dropped (an e-stop mid-take; the teacher decides).
  void Stop() { recording_ = false; }
  /// Ends the recording (if still running) and hands over the episode, with its metadata.
  store::DemoRecord Take();

 private:
  worlds::World& world_;
  Teacher teacher_;
  std::string source_;
  TakeEnd end_;
  store::DemoRecord record_;
  bool recording_ = false;
  double noise_sigma_ = 0.0;
  Rng noise_rng_{0};
};

/// Starts demonstration number `number` of a session whose scenario seeds derive from
/// `session_seed`: its scenario seed is Session::ScenarioSeed(session_seed, number), and in worlds
/// with several demonstrations per configuration it is take number % n of configuration
/// number / n, whose scene is that of the configuration's first demonstration.
void StartSessionDemo(DemoRecorder& recorder, const worlds::World& world, uint64_t session_seed,
                      int number);

/// Puts `world` in the scene demonstration `number` of the session will be recorded in
/// (StartSessionDemo's), without recording: what a teacher sees before pressing Start.
void ShowSessionDemoScene(worlds::World& world, uint64_t session_seed, int number);

/// Starts demo_<number> of the session `manifest` describes, a new take or one recorded again,
/// with the session's injected noise: in its configuration's scene (StartSessionDemo) when
/// `seed` is the session's scenario seed for that number, else in scenario `seed` alone (a take
/// recorded with another --seed).
void StartSessionTake(DemoRecorder& recorder, const worlds::World& world,
                      const store::SessionManifest& manifest, int number, uint64_t seed);

/// Starts play chunk number `number` of a session whose scenario seeds derive from
/// `session_seed` (its own seed: Session::ScenarioSeed(session_seed, number, true)). In worlds
/// with several demonstrations per configuration the chunk is recorded in the scene of
/// demonstration number `number` (configuration number / n), as `recon experiment` records play
/// in each demonstration's scene: the paper's teacher moved the bowl around the plate's marked
/// places, so play covers the plate's places as the demonstrations do (before, chunks drew
/// their own scenes, and one session's 8 chunks had the plate on the same side 7 times).
void StartSessionPlay(PlayRecorder& recorder, const worlds::World& world, uint64_t session_seed,
                      int number, int count);
/// A whole session play chunk (StartSessionPlay), as `recon record --play` records it.
store::PlayRecord RecordSessionPlayChunk(worlds::World& world, uint64_t session_seed, int number,
                                         int count);

/// What `recon record` (and the GUI's "record N demonstrations") does.
struct RecordPlan {
  int demos = 0;
  int play_samples = 0;  ///< recorded in chunks of one scenario each
  uint64_t seed = 1;     ///< scenario seeds derive from this and each episode's number
};

/// Progress of a recording run, reported after every committed episode.
struct RecordProgress {
  int demos_done = 0;
  int play_samples_done = 0;
  std::string last_committed;  ///< e.g. "demo_7 (132 samples, success)"
};

/// Records plan.demos demonstrations and plan.play_samples play samples into `session`, each
/// committed atomically as soon as it is recorded, with the session's demonstration noise
/// (SessionManifest::demo_noise_sigma). Stops between episodes when *cancel becomes
/// true (what is committed stays). The world must have the session's shapes.
void RecordIntoSession(store::Session& session, worlds::World& world, const RecordPlan& plan,
                       const std::function<void(const RecordProgress&)>& on_commit = {},
                       const std::atomic<bool>* cancel = nullptr);

/// Records demonstration `name` again, in its own scenario (its stored seed), and replaces it
/// atomically; the old take moves to the session's trash/ (Session::CommitDemo). What a teacher
/// does with a demonstration that went wrong.
const store::EpisodeEntry& ReRecordDemo(store::Session& session, worlds::World& world,
                                        const std::string& name);

}  // namespace recon::teach
