#include "app/cli/experiment_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/option_checks.h"
#include "app/cli/output_path.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/machine.h"
#include "engine/core/progress.h"
#include "engine/core/strings.h"
#include "engine/experiments/condition.h"
#include "engine/experiments/experiment.h"
#include "engine/experiments/recipe.h"
#include "engine/experiments/summary.h"
#include "engine/learn/learner.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/ur5_arm.h"
#include "engine/worlds/world_factory.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

/// What the user typed; turned into an ExperimentConfig once parsing is done.
struct ExperimentFlags {
  std::string world;
  std::vector<int> demos = {10};
  int runs = 15;
  int tests = 100;
  std::vector<std::string> conditions;
  std::vector<double> noise;
  uint64_t seed = 1;
  std::string out;
  bool force = false;
  int jobs = 0;
  std::string loss = "nll";
  std::string backend = "fused";
  std::string targets;  ///< empty: the recipe's choice
  double learning_rate = 4e-4;
  double beacon_weight = 1.0;  ///< only when --beacon-weight is given
  double play_weight = 1.0;    ///< only when --play-weight is given
  int steps = 6001;
  int baseline_steps = 3001;
  int batch = 20;
  int feature_dim = 6;
  int image_size = 64;
  int play = -1;
  bool restart = true;
  bool authors_compat = false;
  bool authors_recipe = false;
  // The tabletop's protocol (docs/cell.md).
  std::string layout = "paper";
  std::string observation = "image";
  double beacon_noise = worlds::Tabletop::kDwm1001NoiseSigma_m;
  double demo_noise = 0.0;        ///< only when --demo-noise is given; else the world's default
  int random_shift = -1;          ///< -1: the world's recipe
  int random_erase = -1;          ///< -1: the world's recipe
  double feature_noise = 0.0;     ///< only when --feature-noise was given
  int beacon_filter = -1;         ///< -1: the world's recipe
  double play_consistency = 0.0;  ///< only when --play-consistency was given
  double nll_min_std = 0.0;       ///< only when --nll-min-std was given
  double gripper_min_std = 0.0;   ///< only when --gripper-min-std was given
  double weight_decay = 0.0;      ///< only when --weight-decay was given
  int policy_ensemble = 1;
  double feature_gate = 0.0;  ///< the gate margin, only when --feature-gate was given
  bool no_feature_gate = false;
  std::string gate_target;          ///< "loss" | "disagreement"; empty: the world's recipe
  std::string lr_schedule;          ///< "constant" | "cosine"; empty: the world's recipe
  int action_chunk = -1;            ///< -1: the world's recipe
  std::string ensemble;             ///< "all" | "gripper"; empty: the world's recipe
  bool spatial_softmax = false;     ///< only when --spatial-softmax / --no-... was given
  bool standardize_inputs = false;  ///< likewise
};

std::string DefaultOutDir(const std::string& world) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", std::localtime(&now));
  return "out/" + world + "-" + stamp;
}

experiments::ExperimentConfig ToConfig(const ExperimentFlags& flags, const CLI::App& command) {
  experiments::ExperimentConfig config;
  config.world = flags.world;
  const auto given = [&](const char* option) { return command.get_option(option)->count() > 0; };
  const bool conditions_given = command.count("--conditions") > 0;
  const CLI::Option* noise_option = command.get_option_no_throw("--noise");
  const bool noise_given = noise_option != nullptr && noise_option->count() > 0;
  std::vector<std::string> names =
      conditions_given ? flags.conditions : experiments::DefaultConditionNames(flags.world);
  // With no --conditions, dynamic2d runs the paper's whole figure, noise levels included.
  std::vector<double> noise = flags.noise;
  if (!conditions_given && !noise_given && flags.world == "dynamic2d") noise = {2.5, 4.5, 6.5};
  config.conditions = experiments::ParseConditions(flags.world, names, noise);
  if (flags.world == "tabletop") {
    if (flags.observation == "state") {
      config.world = "tabletop-state";
    } else if (flags.observation != "image") {
      throw UserError(
          "--observation must be 'image' (the camera) or 'state' (the objects' true "
          "positions, a diagnostic); got '" +
          flags.observation + "'");
    }
    config.cell.layout = worlds::ChooseLayout(flags.world, flags.layout, "--layout");
    for (experiments::Condition& c : config.conditions) {
      if (c.placement != "none") c.noise_sigma = flags.beacon_noise;
    }
    // Given values win (their option's check has refused absurd ones).
    config.demo_noise =
        given("--demo-noise") ? flags.demo_noise : worlds::DefaultDemoNoise(flags.world);
  }
  config.demos = flags.demos;
  config.runs = flags.runs;
  config.tests = flags.tests;
  config.seed = flags.seed;
  config.authors_compat = flags.authors_compat;
  config.jobs = flags.jobs > 0 ? flags.jobs
                               : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  config.network.feature_dim = flags.feature_dim;
  // --authors-recipe changes the starting point; options typed explicitly still win over it.
  const auto use = [&](const char* option) { return !flags.authors_recipe || given(option); };
  // The world's recipe (recipe.h) for what the user did not set explicitly.
  const experiments::WorldRecipe recipe =
      experiments::RecipeForWorld(config.world, worlds::WorldNeedsRenderer(config.world));
  if (flags.authors_recipe) {
    config.train = learn::AuthorsRecipe();
  } else {
    config.train.learning_rate = recipe.train.learning_rate;
    config.train.steps = recipe.train.steps;
    config.train.beacon_weight = recipe.train.beacon_weight;
    config.train.play_weight = recipe.train.play_weight;
    config.train.lr_schedule = recipe.train.lr_schedule;
  }
  if (use("--loss")) config.train.loss = learn::ParseLossKind(flags.loss);
  if (given("--lr")) config.train.learning_rate = flags.learning_rate;
  if (!flags.lr_schedule.empty()) {
    config.train.lr_schedule = learn::ParseLrSchedule(flags.lr_schedule);
  }
  if (given("--steps")) config.train.steps = flags.steps;
  if (use("--batch")) config.train.batch_size = flags.batch;
  if (use("--restart")) config.train.restart_rule = flags.restart;
  if (given("--beacon-weight")) config.train.beacon_weight = flags.beacon_weight;
  if (given("--play-weight")) config.train.play_weight = flags.play_weight;
  config.train.backend = learn::ParseBackend(flags.backend);
  if (flags.targets == "standardized") {
    config.train.standardize_targets = true;
  } else if (flags.targets == "raw") {
    config.train.standardize_targets = false;
  } else if (!flags.targets.empty()) {
    throw UserError("--targets must be 'standardized' or 'raw' (got '" + flags.targets + "')");
  }
  config.baseline_steps = flags.baseline_steps;
  config.policy_ensemble = flags.policy_ensemble;
  config.play_per_scenario = flags.play;
  config.network.policy_hidden = recipe.network.policy_hidden;
  config.network.image_scale = recipe.network.image_scale;
  config.train.random_shift_px =
      flags.random_shift >= 0 ? flags.random_shift : recipe.train.random_shift_px;
  config.train.random_erase_px =
      flags.random_erase >= 0 ? flags.random_erase : recipe.train.random_erase_px;
  config.train.feature_noise =
      given("--feature-noise") ? flags.feature_noise : recipe.train.feature_noise;
  config.train.beacon_filter_samples =
      flags.beacon_filter >= 0 ? flags.beacon_filter : recipe.train.beacon_filter_samples;
  config.train.play_consistency =
      given("--play-consistency") ? flags.play_consistency : recipe.train.play_consistency;
  config.train.nll_min_std = given("--nll-min-std") ? flags.nll_min_std : recipe.train.nll_min_std;
  config.train.action_min_std = recipe.train.action_min_std;
  config.train.weight_decay =
      given("--weight-decay") ? flags.weight_decay : recipe.train.weight_decay;
  if (given("--gripper-min-std")) {
    if (flags.world != "tabletop") {
      throw UserError("--gripper-min-std: the " + flags.world +
                      " world has no gripper command (use --nll-min-std)");
    }
    // u = the arm's joint velocities, then the gripper command.
    config.train.action_min_std.assign(worlds::Ur5Arm::kJoints + 1, 0.0);
    config.train.action_min_std[worlds::Ur5Arm::kJoints] = flags.gripper_min_std;
  }
  config.network.feature_gate_hidden = recipe.network.feature_gate_hidden;
  config.train.gate_margin = recipe.train.gate_margin;
  if (given("--feature-gate")) {
    config.network.feature_gate_hidden = experiments::kFeatureGateHidden;
    config.train.gate_margin = flags.feature_gate;
  } else if (flags.no_feature_gate) {
    config.network.feature_gate_hidden.clear();
    config.train.gate_margin = 0.0;
  }
  config.train.gate_target = recipe.train.gate_target;
  if (!flags.gate_target.empty()) {
    if (!config.network.has_feature_gate()) {
      throw UserError("--gate-target: there is no feature gate to train (add --feature-gate M)");
    }
    config.train.gate_target = learn::ParseGateTarget(flags.gate_target);
  }
  if (!worlds::WorldNeedsRenderer(config.world)) {
    // Vector observations have no pixels to shift or erase.
    if (flags.random_shift < 0) config.train.random_shift_px = 0;
    if (flags.random_erase > 0) {
      throw UserError("--random-erase: the " + config.world +
                      " world's observations are vectors, not camera images");
    }
    config.train.random_erase_px = 0;
  }
  config.network.action_chunk =
      flags.action_chunk >= 0 ? flags.action_chunk : recipe.network.action_chunk;
  config.network.ensembled_actions = recipe.network.ensembled_actions;
  if (flags.ensemble == "all") {
    config.network.ensembled_actions.clear();
  } else if (flags.ensemble == "gripper") {
    if (flags.world != "tabletop" && flags.world != "bintransfer") {
      throw UserError("--ensemble gripper: the " + flags.world + " world has no gripper (use all)");
    }
    config.network.ensembled_actions = {worlds::Ur5Arm::kJoints};  // u = joints..., gripper
  }
  config.network.spatial_softmax =
      given("--spatial-softmax") ? flags.spatial_softmax : recipe.network.spatial_softmax;
  config.train.standardize_inputs =
      given("--standardize-inputs") ? flags.standardize_inputs : recipe.train.standardize_inputs;
  if (!given("--restart")) config.train.restart_rule = recipe.train.restart_rule;
  if (flags.world == "bintransfer" || flags.world == "tabletop") {
    // Halving the Baseline's steps is the authors' Dynamic 2D habit; here both train as long.
    if (!given("--baseline-steps")) config.baseline_steps = config.train.steps;
  }
  if (worlds::WorldNeedsRenderer(config.world)) {
    config.cell.renderer_factory = render::MujocoRendererFactory();
    config.cell.image_size = flags.image_size;
  }
  return config;
}

void PrintTable(const std::vector<experiments::ConditionSummary>& summaries,
                const experiments::ExperimentResult& result) {
  const bool success = result.has_success;
  std::printf("\n%-16s %6s %9s %7s %4s %6s%s  %s\n", "condition", "demos", "mean", "sem", "n",
              "steps", success ? "  success" : "",
              result.higher_is_better ? "(higher is better)" : "(lower is better)");
  for (const auto& s : summaries) {
    char rate[32] = "";
    if (success) std::snprintf(rate, sizeof(rate), "  %6.0f%%", 100.0 * s.success_rate);
    std::printf("%-16s %6d %9.3f %7.3f %4d %6d%s%s\n", s.condition.c_str(), s.demos, s.mean, s.sem,
                s.n, s.train_steps, rate,
                s.diverged > 0 ? ("  (" + std::to_string(s.diverged) + " diverged)").c_str() : "");
  }
  std::printf("%-16s %6s %9.3f\n", "expert", "", result.expert_metric);
}

void Run(const ExperimentFlags& flags, const CLI::App& command, const GlobalOptions& global) {
  const experiments::ExperimentConfig config = ToConfig(flags, command);
  experiments::ValidateExperimentConfig(config);
  const std::string out = flags.out.empty() ? DefaultOutDir(flags.world) : flags.out;
  // Fail before an hour of training, not after: the folder must be writable, and results of an
  // earlier experiment are never replaced unless asked.
  CheckOutputFolder("--out", out, flags.force, "summary.json");
  if (fs::exists(fs::path(out) / "summary.json") && !flags.force) {
    throw UserError(out +
                    " already holds an experiment's results (summary.json); choose "
                    "another --out or pass --force to replace them");
  }
  EnsureWritableDirectory(out);
  learn::SetThreads(global.threads);

  const int total = static_cast<int>(config.conditions.size() * config.demos.size()) * config.runs;
  std::printf(
      "recon experiment %s: %zu conditions x %zu demo counts x %d runs = %d models, "
      "%d test scenarios, seed %llu, %d parallel jobs x %d thread(s), kernels %s on %s\n",
      config.world.c_str(), config.conditions.size(), config.demos.size(), config.runs, total,
      config.tests, static_cast<unsigned long long>(config.seed), config.jobs, global.threads,
      learn::KernelsInUse().c_str(), CpuModelName().c_str());
  std::fflush(stdout);
  std::printf("each finished run is kept in %s until the results are written\n",
              (fs::path(out) / experiments::kRunsSoFarFile).c_str());
  std::fflush(stdout);
  ProgressLine progress("training", total);
  std::vector<experiments::RunResult> finished;  // the runner calls back one run at a time
  const experiments::ExperimentResult result =
      experiments::RunExperiment(config, [&](const experiments::RunResult& r) {
        finished.push_back(r);
        experiments::WriteRunsSoFar(finished, out);
        char detail[128];
        std::snprintf(detail, sizeof(detail), "%s demos %d run %d: %.3f", r.condition.c_str(),
                      r.demos, r.run, r.metric);
        progress.Advance(1, detail);
      });
  progress.Finish();

  const std::vector<std::string> written = experiments::WriteExperimentOutputs(config, result, out);
  PrintTable(experiments::Summarize(config, result), result);
  std::printf("\nwall time %.1f s\n", result.wall_seconds);
  for (const std::string& path : written) std::printf("wrote %s\n", path.c_str());
}

// A world's defaults: the paper's protocol for that experiment.
struct WorldDefaults {
  int runs = 15;
  int tests = 100;
  std::vector<int> demos = {10};
};

void AddWorldCommand(CLI::App& experiment, const std::string& world, const std::string& help,
                     const WorldDefaults& defaults, const GlobalOptions& global) {
  auto flags = std::make_shared<ExperimentFlags>();
  flags->world = world;
  flags->runs = defaults.runs;
  flags->tests = defaults.tests;
  flags->demos = defaults.demos;
  CLI::App* command = experiment.add_subcommand(world, help);
  command->add_option("--demos", flags->demos, "demonstrations per run; a list sweeps them")
      ->delimiter(',')
      ->check(WholeBetween(1, kMaxDemos))
      ->capture_default_str();
  command->add_option("--runs", flags->runs, "training runs per condition")
      ->check(WholeBetween(1, kMaxRuns))
      ->capture_default_str();
  command->add_option("--tests", flags->tests, "test scenarios")
      ->check(WholeBetween(1, kMaxTests))
      ->capture_default_str();
  command
      ->add_option(
          "--conditions", flags->conditions,
          "conditions to run, from: " + JoinNames(experiments::KnownConditionNames(world), ","))
      ->delimiter(',');
  if (world == "dynamic2d") {
    command
        ->add_option("--noise", flags->noise,
                     "beacon noise sigmas for extra Exact conditions (default with no "
                     "--conditions: 2.5,4.5,6.5)")
        ->delimiter(',')
        ->check(PositiveNumberUpTo(kMaxDynamicNoise));
    command->add_flag("--authors-compat", flags->authors_compat,
                      "reproduce the authors' two slips (docs/worlds.md)");
  }
  command->add_option("--seed", flags->seed, "master seed")
      ->check(SeedNumber())
      ->capture_default_str();
  command->add_option("--out", flags->out, "output folder (default out/<world>-<time>)");
  command->add_flag("--force", flags->force, "replace the results already in --out");
  command->add_option("--jobs", flags->jobs, "runs trained in parallel (default: cores)")
      ->check(WholeBetween(1, ParallelismLimit()));
  command->add_option("--loss", flags->loss, "nll (paper) or mse-sample (authors' code)")
      ->capture_default_str();
  command
      ->add_option("--backend", flags->backend,
                   "fused (our kernels, checked against LibTorch autograd) or torch (LibTorch "
                   "operators and autograd; about 3x slower)")
      ->capture_default_str();
  command->add_option("--targets", flags->targets,
                      "standardized or raw action/beacon targets (default: standardized, raw "
                      "with --authors-recipe)");
  command
      ->add_option("--lr", flags->learning_rate,
                   "Adam learning rate (default: the world's recipe: 0.0004, the authors'; "
                   "tabletop 0.001)")
      ->check(PositiveNumberUpTo(kMaxLearningRate));
  command
      ->add_option("--lr-schedule", flags->lr_schedule,
                   "constant or cosine (decay to 0 over the run) learning rate (default: the "
                   "world's recipe)")
      ->check(CLI::IsMember({"constant", "cosine"}));
  command
      ->add_option("--beacon-weight", flags->beacon_weight,
                   "weight of RECON's beacon term (default: the world's recipe: 1, the "
                   "paper's, 0.1 on the tabletop; 1.2 with --authors-recipe)")
      ->check(NumberBetween(0, kMaxTermWeight));
  command
      ->add_option("--play-weight", flags->play_weight,
                   "weight of RECON's play term (default: the world's recipe: 1, the "
                   "paper's, 0.1 on the tabletop; 1.2 with --authors-recipe)")
      ->check(NumberBetween(0, kMaxTermWeight));
  command
      ->add_option("--steps", flags->steps,
                   "training steps with beacons (default: the world's recipe: 6001, the "
                   "authors'; tabletop 7500, tabletop-state 15000)")
      ->check(WholeBetween(1, kMaxSteps));
  command->add_option("--baseline-steps", flags->baseline_steps, "training steps of the Baseline")
      ->check(WholeBetween(1, kMaxSteps))
      ->capture_default_str();
  command->add_option("--batch", flags->batch, "batch size")
      ->check(WholeBetween(1, kMaxBatch))
      ->capture_default_str();
  command
      ->add_option("--play", flags->play,
                   "play samples per demonstration scenario for play conditions (default: "
                   "the world's recipe, 3)")
      ->check(WholeBetween(0, kMaxPlay));
  command->add_option("--feature-dim", flags->feature_dim, "feature size k (must exceed d)")
      ->check(WholeBetween(1, kMaxFeatureDim))
      ->capture_default_str();
  command
      ->add_option("--random-shift", flags->random_shift,
                   "random-shift augmentation of camera images, pixels (DrQ; 0 = off; default: "
                   "the world's recipe)")
      ->check(WholeBetween(0, 16));
  command
      ->add_option("--random-erase", flags->random_erase,
                   "random erasing of camera images: a square of N x N pixels painted with the "
                   "image's mean colour, at a random place of each training image (cutout; 0 = "
                   "off; default: the world's recipe)")
      ->check(WholeBetween(0, learn::kMaxRandomErasePx));
  command
      ->add_option("--feature-noise", flags->feature_noise,
                   "noise on the features the policy reads while training, in standard "
                   "deviations of each feature over the batch (0 = off; default: the world's "
                   "recipe)")
      ->check(NumberBetween(0, learn::kMaxFeatureNoise));
  command
      ->add_option("--beacon-filter", flags->beacon_filter,
                   "beacon readings are trained on as the mean of the readings up to N samples "
                   "before and after them in the same take (0 = raw; default: the world's "
                   "recipe)")
      ->check(WholeBetween(0, learn::kMaxBeaconFilterSamples));
  command
      ->add_option("--play-consistency", flags->play_consistency,
                   "weight of a RECON term that asks the features of two play samples of one "
                   "beacon placement to agree (0 = off, the paper's RECON; default: the world's "
                   "recipe)")
      ->check(NumberBetween(0, learn::kMaxPlayConsistency));
  command
      ->add_option("--nll-min-std", flags->nll_min_std,
                   "a floor under the standard deviation of the NLL's Gaussian heads, in "
                   "standardised target units (0 = none, the paper's; default: the world's "
                   "recipe)")
      ->check(NumberBetween(0, learn::kMaxNllMinStd));
  command
      ->add_option("--gripper-min-std", flags->gripper_min_std,
                   "tabletop: a floor like --nll-min-std under the policy's spread of the gripper "
                   "command alone, the joints' untouched (0 = none; default: the world's recipe)")
      ->check(NumberBetween(0, learn::kMaxNllMinStd));
  command
      ->add_option("--policy-ensemble", flags->policy_ensemble,
                   "models trained per run from different seeds that act as one (their mean "
                   "action; a deep ensemble), both methods alike; 1 = one model, the paper's")
      ->check(WholeBetween(1, experiments::kMaxPolicyEnsemble));
  command
      ->add_option("--weight-decay", flags->weight_decay,
                   "decoupled weight decay (AdamW) of every network's weights, per unit of "
                   "learning rate; both methods alike (0 = off, the paper's; default: the "
                   "world's recipe)")
      ->check(NumberBetween(0, learn::kMaxWeightDecay));
  CLI::Option* gate =
      command
          ->add_option("--feature-gate", flags->feature_gate,
                       "a gate on the robot state that shuts the features out of the policy "
                       "where they do not help; the value is the margin of its targets (see "
                       "--gate-target; 0-" +
                           FormatNumber(learn::kMaxGateMargin) + "; default: the world's recipe)")
          ->check(NumberBetween(0, learn::kMaxGateMargin));
  command->add_flag("--no-feature-gate", flags->no_feature_gate, "no feature gate")->excludes(gate);
  command
      ->add_option("--gate-target", flags->gate_target,
                   "where the feature gate learns to open: loss (where seeing lowers the action "
                   "loss by more than the margin, nats per action) or disagreement (where another "
                   "demonstration's teacher acted otherwise near the nearest state by more than "
                   "the margin, in units of the actions' total variance, for at least two chunks' "
                   "steps; docs/learning.md); default: the world's recipe")
      ->check(CLI::IsMember({"loss", "disagreement"}));
  command
      ->add_option("--action-chunk", flags->action_chunk,
                   "actions predicted at once and ensembled over steps (ACT; 1 = off; default: "
                   "the world's recipe)")
      ->check(WholeBetween(1, 100));
  command
      ->add_option("--ensemble", flags->ensemble,
                   "which actions a chunked policy averages over its overlapping chunks: all "
                   "(ACT) or gripper (the gripper command; the joints act on the newest chunk); "
                   "default: the world's recipe")
      ->check(CLI::IsMember({"all", "gripper"}));
  command->add_flag(
      "--spatial-softmax,!--no-spatial-softmax", flags->spatial_softmax,
      "end the CNN in a spatial-softmax keypoint layer (default: the world's recipe)");
  command->add_flag("--standardize-inputs,!--no-standardize-inputs", flags->standardize_inputs,
                    "standardise the robot state x (and a vector y) per dimension (default: the "
                    "world's recipe)");
  if (worlds::WorldNeedsRenderer(world)) {
    command->add_option("--image-size", flags->image_size, "camera images are N x N pixels")
        ->check(WholeBetween(16, 480))
        ->capture_default_str();
  }
  if (world == "tabletop") {
    command
        ->add_option("--layout", flags->layout,
                     "paper (the plate at one of two places, 2 demonstrations per configuration) "
                     "or wide (the plate anywhere along either edge)")
        ->capture_default_str();
    command
        ->add_option("--noise", flags->beacon_noise,
                     "beacon noise sigma per axis, metres (default: a DWM1001's; 0 = exact)")
        ->check(NumberBetween(0, kMaxBeaconNoise_m))
        ->capture_default_str();
    command
        ->add_option("--demo-noise", flags->demo_noise,
                     "noise injected into the executed joint velocities while demonstrating "
                     "(DART), rad/s; 0 = off (the default)")
        ->check(NumberBetween(0, kMaxDemoNoise_rad_s));
    command
        ->add_option("--observation", flags->observation,
                     "image (the camera) or state (the objects' true positions: a diagnostic of "
                     "what is lost to vision)")
        ->capture_default_str();
  }
  command->add_flag("--restart,!--no-restart", flags->restart,
                    "retrain a run from a new seed stream when its final training error is bad "
                    "(the authors' rule; on by default)");
  command->add_flag("--authors-recipe", flags->authors_recipe,
                    "start from the authors' recipe: mse-sample loss, weights 1/1.2/1.2, raw "
                    "targets, restarts (options given explicitly still apply)");
  command->callback([flags, command, &global] { Run(*flags, *command, global); });
}

}  // namespace

void AddExperimentCommands(CLI::App& app, const GlobalOptions& global) {
  CLI::App* experiment =
      app.add_subcommand("experiment", "reproduce one of the paper's experiments");
  experiment->require_subcommand(1);
  AddWorldCommand(*experiment, "dynamic2d",
                  "Dynamic 2D: beacon placements and noise (paper Fig. 5)", {15, 100, {10}},
                  global);
  AddWorldCommand(*experiment, "static2d",
                  "Static 2D: position/distance beacons with and without play (paper Fig. 4)",
                  {20, 100, {10}}, global);
  AddWorldCommand(*experiment, "bintransfer",
                  "Bin transfer with the simulated UR5: action error against the expert (paper "
                  "Fig. 4, right)",
                  {20, 110, {10}}, global);
  AddWorldCommand(*experiment, "tabletop",
                  "Tabletop with the simulated UR5 and camera: toast to plate, beacons removed "
                  "at test (paper Sec. V)",
                  {3, 20, {4, 6}}, global);
}

}  // namespace recon::cli
