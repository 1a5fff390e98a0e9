#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::worlds {

/// What the robot observes at one step: its own state x and the environment observation y.
struct Observation {
  std::vector<float> x;
  std::vector<float> y;
};

/// What kind of task a world is: what its metric means and which capabilities it has, one struct
/// per world (World::Traits) rather than a virtual method per flag, so a new capability is a
/// field with a default instead of another method every world must consider.
struct WorldTraits {
  /// Name and unit of the metric, e.g. "final distance to the red object".
  std::string metric_name;
  /// The metric's short name for tables and JSON ("distance", "reward", "action_mse"); empty:
  /// "reward" when higher_is_better, else "distance".
  std::string metric_key;
  /// A larger metric is better (reward); otherwise a smaller one is (distance, error).
  bool higher_is_better = false;
  /// The task has a notion of success (the robot worlds), which experiments then report as a
  /// success rate beside the metric.
  bool has_success = false;
  /// A policy is scored by its action error along the expert's own demonstration of each test
  /// scenario (the paper's BinTransfer metric: action MSE against the expert) instead of by the
  /// outcome of its own rollout.
  bool scores_actions = false;
  /// Seconds of teaching one step stands for (the control period of a robot world, whose
  /// demonstrations cost the teacher real time); 0 for the abstract 2-D worlds.
  double step_seconds = 0.0;
};

/// Where a tool may put a world's movable objects (ObjectLayout's), for the distractor probe
/// (engine/probe): the table's extent in x and y (metres, table frame) and each object's
/// footprint radius, so objects are not placed into one another.
struct ObjectArea {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
  std::map<std::string, double> radius_m;
};

/// A task the robot is taught: scenarios, dynamics, an expert, beacons and a score.
///
/// A World is configured with one beacon placement at construction (the placement decides
/// b's size). Reset(seed) draws a new scenario; everything random in the scenario (layout,
/// image background, which object a Random beacon lands on, beacon noise) comes from that
/// seed, so a scenario is reproduced exactly by its seed.
class World {
 public:
  virtual ~World() = default;

  /// Short lower-case name, e.g. "dynamic2d".
  virtual std::string Name() const = 0;
  /// Shapes of x, y, b, u under the configured placement.
  virtual DataSpec Spec() const = 0;
  /// Steps in a demonstration and in an evaluation rollout.
  virtual int EpisodeLength() const = 0;

  /// Starts a new scenario drawn from `seed`.
  virtual void Reset(uint64_t seed) = 0;
  /// How many demonstrations a teacher records per scene configuration. The paper's robot
  /// experiment records 2 takes of each plate-and-bowl configuration (4 demonstrations = 2
  /// configurations); 1 (the default) makes every demonstration a scenario of its own.
  virtual int DemosPerConfiguration() const { return 1; }
  /// How many demonstrations the world's protocol asks for before training (the studio points
  /// to Train once they are kept): on the tabletop the paper's four, two takes on each side of
  /// the table. 1 (the default): one demonstration is enough to train.
  virtual int SuggestedDemos() const { return 1; }
  /// Starts a demonstration take: the scene of configuration number `configuration` (0, 1, ...),
  /// drawn from `configuration_seed` (the scenario seed of the configuration's first take), with
  /// the take's own randomness (beacon noise, play data) from `seed`. Takes of one configuration
  /// share the scene and differ in everything else. The default is Reset(seed), which is right
  /// for worlds with one demonstration per configuration.
  virtual void ResetTake(uint64_t seed, uint64_t configuration_seed, int configuration) {
    (void)configuration_seed;
    (void)configuration;
    Reset(seed);
  }
  /// Per action dimension, how strongly a recording may perturb the executed action when noise
  /// injection is on (DART): 1 for a joint velocity, 0 for a gripper command that must not
  /// flicker. Empty (the default): the world's actions are never perturbed.
  virtual std::vector<float> ActionNoiseScale() const { return {}; }
  virtual Observation Observe() const = 0;
  /// Applies action u (size Spec().u_dim) and advances the world one step.
  virtual void Step(const std::vector<float>& u) = 0;
  /// The demonstrator's action in the current state.
  virtual std::vector<float> ExpertAction() const = 0;
  /// The beacon reading b in the current state under the configured placement (with noise if
  /// configured). Empty when the placement is "none".
  virtual std::vector<float> BeaconReading() = 0;
  /// Draws one play-data sample (x, y, b) from the current scenario without changing it.
  virtual PlaySample SamplePlay() = 0;
  /// Play samples drawn per recorded scenario in the authors' recipe.
  virtual int PlaySamplesPerScenario() const = 0;

  /// The score of the current state at the end of a rollout.
  virtual double EpisodeMetric() const = 0;
  /// What kind of task this is (WorldTraits); the shorthands below read it.
  virtual WorldTraits Traits() const = 0;
  bool HigherIsBetter() const { return Traits().higher_is_better; }
  std::string MetricName() const { return Traits().metric_name; }
  /// WorldTraits::metric_key, or its default from higher_is_better.
  std::string MetricKey() const;
  bool HasSuccess() const { return Traits().has_success; }
  bool ScoresActions() const { return Traits().scores_actions; }
  double StepSeconds() const { return Traits().step_seconds; }
  /// True when the demonstrator has finished in the current state, so recording stops before
  /// EpisodeLength() (a teacher stops the recording once the task is done, rather than recording
  /// the arm standing still). Rollouts always run EpisodeLength() steps. Default: never.
  virtual bool DemonstrationDone() const { return false; }
  /// A person's take is over: the task's goal holds and the arm has let go of what it moved and
  /// is clear of it, wherever the arm is (a person does not aim for the scripted teacher's end
  /// point). The studio ends keyboard and gamepad takes here, and counts a take that ran out of
  /// time with the goal holding (TaskSucceeded) as done. Default: DemonstrationDone().
  virtual bool GoalHoldsAndClear() const { return DemonstrationDone(); }
  /// Whether the task is done in the current state (false when !HasSuccess()).
  virtual bool TaskSucceeded() const { return false; }
  /// Named facts about the end state that explain an outcome, each a number averaged over test
  /// scenarios in the experiment summary (e.g. tabletop's "toast_moved": 1 if the toast left its
  /// pick-up place). Empty by default.
  virtual std::map<std::string, double> OutcomeDetails() const { return {}; }
  /// Where the scene's movable objects stand (table x, y in metres), by name: what a person sets
  /// up to give a real cell this scene. Empty where the world has no such objects (the default).
  virtual std::map<std::string, std::array<double, 2>> ObjectLayout() const { return {}; }
  /// What it takes to draw the current step again later (a rollout played back frame by frame
  /// beside another on the same scene), as a vector of a fixed size per world configuration;
  /// empty when the world has no replay (the default).
  virtual std::vector<double> ReplayState() const { return {}; }
  /// Puts the world in a state ReplayState() returned, for drawing only (camera image, object
  /// positions): whatever the world does not need to draw (velocities, the controller, a grasp)
  /// is not restored, so Reset() before stepping again. UserError when the world has no replay,
  /// or naming the expected and the actual size when `state` has the wrong size.
  virtual void ShowReplayState(const std::vector<double>& state) {
    (void)state;
    throw UserError("the " + Name() + " world has no replay: its rollouts cannot be shown again");
  }
  /// The area objects may be placed in (PlaceObject); none where the world cannot move them
  /// (the default).
  virtual std::optional<ObjectArea> PlaceableArea() const { return std::nullopt; }
  /// Moves `object` (one of ObjectLayout's) to table (x, y) with everything else held, and
  /// observes again: Observe() shows the scene with the object there, and stepping from there
  /// rolls out from the scene so arranged (the outcome probe). UserError naming the valid
  /// objects for an unknown one, or when the world cannot move its objects.
  virtual void PlaceObject(const std::string& object, const std::array<double, 2>& xy) {
    (void)object;
    (void)xy;
    throw UserError("the " + Name() + " world cannot move its objects");
  }
  /// Whether the task can be done at all in the scene as it stands (e.g. every place the arm
  /// must reach is within its reach), after objects were placed by hand.
  virtual bool TaskFeasible() const { return true; }
};

/// Noise injected into the executed action while demonstrating (DART, Laskey et al. 2017): the
/// arm moves with u + sigma * scale * N(0, 1) (scale from World::ActionNoiseScale) while the
/// teacher's own u is stored as the label, so the data shows how the teacher recovers from the
/// small errors a learner will make. sigma = 0 is off.
struct DemoNoise {
  double sigma = 0.0;  ///< in the action's units (rad/s for the arm worlds), at most kMaxDemoNoise
  /// Each take's noise is drawn from Derive(seed, take seed): reproducible per take.
  uint64_t seed = 0;
};

/// The largest DemoNoise::sigma a session or an experiment accepts (action units).
constexpr double kMaxDemoNoise = 1.0;
/// The largest beacon noise (per-axis sigma, metres) a world, a session or an experiment
/// accepts: more is no beacon at all (the tabletop is 1 m across).
constexpr double kMaxBeaconNoise_m = 0.5;

/// A run's demonstrations are grouped into configurations: demonstration i is take i % n of
/// configuration i / n (n = World::DemosPerConfiguration), and a configuration's scene comes from
/// the scenario seed of its first take. UserError when `demos` is not a multiple of n, naming
/// `option`, n and how the demonstrations would have split.
void CheckDemosFillConfigurations(const World& world, int demos, const std::string& option);

/// Resets `world` for demonstration `index` of `seeds` (see CheckDemosFillConfigurations).
void ResetForDemo(World& world, const std::vector<uint64_t>& seeds, size_t index);

/// Perturbs an action for execution (DemoNoise); returns u unchanged when noise is off or the
/// world has no noise scale.
std::vector<float> PerturbAction(const World& world, const std::vector<float>& u, double sigma,
                                 Rng& rng);

/// Records one demonstration per seed: ResetForDemo, then up to EpisodeLength() steps of
/// (x, y, b, u) with the expert acting (fewer when DemonstrationDone() says the teacher stopped);
/// also `play_per_scenario` play samples per scenario (drawn from the initial scenario before the
/// demonstration runs). With `noise`, the executed actions are perturbed and the expert's
/// actions kept as labels. Used by experiments and by `recon record`.
Dataset RecordDemonstrations(World& world, const std::vector<uint64_t>& seeds,
                             int play_per_scenario, const DemoNoise& noise = {});

/// A policy as the world sees it: an action for an observation. No beacon: a trained policy never
/// needs one.
using PolicyFn = std::function<std::vector<float>(const Observation&)>;

/// Resets to `seed`, runs `policy` for EpisodeLength() steps and returns EpisodeMetric().
double Rollout(World& world, uint64_t seed, const PolicyFn& policy);

}  // namespace recon::worlds
