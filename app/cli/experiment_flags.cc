#include "app/cli/experiment_flags.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/option_checks.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/core/machine.h"
#include "engine/core/strings.h"
#include "engine/experiments/condition.h"
#include "engine/experiments/recipe.h"
#include "engine/learn/learner.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/ur5_arm.h"
#include "engine/worlds/world_factory.h"

namespace recon::cli {

const std::vector<std::string>& ExperimentWorlds() {
  static const std::vector<std::string> worlds = {"dynamic2d", "static2d", "bintransfer",
                                                  "tabletop"};
  return worlds;
}

WorldDefaults DefaultsOf(const std::string& world) {
  if (world == "static2d") return {20, 100, {10}};
  if (world == "bintransfer") return {20, 110, {10}};
  if (world == "tabletop") return {3, 20, {4, 6}};
  return {15, 100, {10}};  // dynamic2d
}

std::string ExperimentHelp(const std::string& world) {
  if (world == "static2d") {
    return "Static 2D: position/distance beacons with and without play (paper Fig. 4)";
  }
  if (world == "bintransfer") {
    return "Bin transfer with the simulated UR5: action error against the expert (paper Fig. 4, "
           "right)";
  }
  if (world == "tabletop") {
    return "Tabletop with the simulated UR5 and camera: toast to plate, beacons removed at test "
           "(paper Sec. V)";
  }
  return "Dynamic 2D: beacon placements and noise (paper Fig. 5)";
}

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
    const auto& teachers = experiments::ExperimentTeachers();
    if (std::find(teachers.begin(), teachers.end(), flags.teacher) == teachers.end()) {
      throw UserError("--teacher must be one of " + JoinNames(teachers) + "; got '" +
                      flags.teacher + "'");
    }
    if (flags.teacher == "person" && config.world != "tabletop") {
      throw UserError("--teacher person teaches from the camera only (--observation image)");
    }
    if (flags.teacher == "person" && config.demo_noise > 0) {
      throw UserError(
          "--demo-noise: the simulated person's takes carry no injected noise (its "
          "own imprecision is the point); drop --demo-noise or use --teacher expert");
    }
    config.teacher = flags.teacher;
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
  const experiments::WorldRecipe recipe = experiments::RecipeForWorld(
      config.world, worlds::WorldNeedsRenderer(config.world), flags.teacher == "person");
  if (!flags.keep_pauses) config.pause_motion = recipe.pause_motion;
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
    // Vector observations have no pixels to shift or erase. Refused here, before anything is
    // written into --out, rather than by the first unit.
    for (const auto& [option, pixels] : {std::pair{"--random-shift", flags.random_shift},
                                         {"--random-erase", flags.random_erase}}) {
      if (pixels > 0) {
        throw UserError(std::string(option) + ": the " + config.world +
                        " world's observations are vectors, not camera images");
      }
    }
    config.train.random_shift_px = 0;
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

}  // namespace recon::cli
