#include "app/cli/experiment_command.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/experiment_flags.h"
#include "app/cli/option_checks.h"
#include "app/cli/output_path.h"
#include "app/cli/run_main.h"
#include "app/cli/slurm_commands.h"
#include "app/cli/sweep_commands.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/machine.h"
#include "engine/core/progress.h"
#include "engine/core/strings.h"
#include "engine/experiments/condition.h"
#include "engine/experiments/experiment.h"
#include "engine/experiments/summary.h"
#include "engine/learn/learner.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/world_factory.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

void Run(const ExperimentFlags& flags, const CLI::App& command, const GlobalOptions& global) {
  const experiments::ExperimentConfig config = ToConfig(flags, command);
  experiments::ValidateExperimentConfig(config);
  const std::string out = flags.out.empty() ? DefaultOutDir(flags.world) : flags.out;
  // Fail before an hour of training, not after: the folder must be writable, and results of an
  // earlier experiment are never replaced unless asked.
  // A folder with this sweep's plan is resumed (PlanSweep refuses another sweep's).
  if (!fs::exists(experiments::PlanPath(out))) {
    CheckOutputFolder("--out", out, flags.force, "summary.json");
  }
  if (fs::exists(fs::path(out) / "summary.json") && !flags.force) {
    throw UserError(out +
                    " already holds an experiment's results (summary.json); choose "
                    "another --out or pass --force to replace them");
  }
  EnsureWritableDirectory(out);
  learn::SetThreads(global.threads);

  // One code path: the plan, its units (here on the local cores), and the collection.
  const experiments::SweepPlan plan =
      PlanSweep(config, SweepArguments(CommandLine()), out, flags.force);
  const int total = static_cast<int>(plan.units.size());
  if (flags.plan_only) {
    std::printf(
        "planned %d units into %s (%s): run each with `recon experiment run-unit %s --unit K` "
        "(K from 0 to %d), here or on a cluster's nodes, then `recon experiment collect %s`\n",
        total, out.c_str(), experiments::PlanPath(out).c_str(), out.c_str(), total - 1,
        out.c_str());
    return;
  }
  std::printf(
      "recon experiment %s: %zu conditions x %zu demo counts x %d runs = %d models, "
      "%d test scenarios, seed %llu, %d parallel jobs x %d thread(s), kernels %s on %s\n",
      config.world.c_str(), config.conditions.size(), config.demos.size(), config.runs, total,
      config.tests, static_cast<unsigned long long>(config.seed), config.jobs, global.threads,
      learn::KernelsInUse().c_str(), CpuModelName().c_str());
  std::printf("each finished run is kept in %s and %s until the results are written\n",
              (fs::path(out) / "units").c_str(),
              (fs::path(out) / experiments::kRunsSoFarFile).c_str());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  ProgressLine progress("training", total);
  std::vector<experiments::RunResult> finished;  // the runner calls back one unit at a time
  RunUnitsLocally(config, plan, out, config.jobs, [&](const experiments::UnitResult& u) {
    finished.push_back(u.run);
    experiments::WriteRunsSoFar(finished, out);
    char detail[128];
    std::snprintf(detail, sizeof(detail), "%s demos %d run %d: %.3f", u.run.condition.c_str(),
                  u.run.demos, u.run.run, u.run.metric);
    progress.Advance(1, detail);
  });
  progress.Finish();
  CollectSweep(out, true);
  std::printf("\nwall time %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

// The paper's protocol for each world is the defaults (DefaultsOf). The callback is the
// caller's: the command line runs it; a sweep's unit only reads the flags back.
CLI::App* AddWorldOptions(CLI::App& experiment, const std::string& world, const std::string& help,
                          const std::shared_ptr<ExperimentFlags>& flags) {
  const WorldDefaults defaults = DefaultsOf(world);
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
      ->check(NumberBetween(learn::kMinLearningRate, kMaxLearningRate));
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
    command->add_flag("--keep-pauses", flags->keep_pauses,
                      "train on the demonstrations' pauses too (commands that move nothing and "
                      "change nothing), which the recipe leaves out; both methods alike");
    command
        ->add_option("--teacher", flags->teacher,
                     "who gives the demonstrations: expert (the scripted teacher) or person (a "
                     "simulated person at the keyboard: reaction times, overshoot, pauses, "
                     "missed grasps; docs/learning.md)")
        ->capture_default_str();
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
  command->add_flag("--plan-only", flags->plan_only,
                    "write the sweep's plan into --out and stop: its units are run by `recon "
                    "experiment run-unit` (here or on a cluster) and gathered by `recon "
                    "experiment collect`");
  return command;
}

namespace {

void AddWorldCommand(CLI::App& experiment, const std::string& world, const std::string& help,
                     const GlobalOptions& global) {
  auto flags = std::make_shared<ExperimentFlags>();
  CLI::App* command = AddWorldOptions(experiment, world, help, flags);
  command->callback([flags, command, &global] { Run(*flags, *command, global); });
}

}  // namespace

void AddExperimentCommands(CLI::App& app, const GlobalOptions& global) {
  CLI::App* experiment =
      app.add_subcommand("experiment", "reproduce one of the paper's experiments");
  experiment->require_subcommand(1);
  // What each world's experiment is, and the paper's protocol for it.
  for (const std::string& world : ExperimentWorlds()) {
    AddWorldCommand(*experiment, world, ExperimentHelp(world), global);
  }
  AddSweepCommands(*experiment, global);
  AddSlurmCommands(*experiment);
}

}  // namespace recon::cli
