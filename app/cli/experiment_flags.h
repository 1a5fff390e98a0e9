#pragma once

// What `recon experiment <world>` was given, and the experiment it asks for.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/experiments/experiment.h"
#include "engine/worlds/tabletop.h"

namespace recon::cli {

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
  bool plan_only = false;  ///< write the sweep's plan and stop
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
  double demo_noise = 0.0;         ///< only when --demo-noise is given; else the world's default
  std::string teacher = "expert";  ///< who demonstrates (tabletop): expert or person
  bool keep_pauses = false;        ///< train on a person's pauses too (the recipe leaves them out)
  int random_shift = -1;           ///< -1: the world's recipe
  int random_erase = -1;           ///< -1: the world's recipe
  double feature_noise = 0.0;      ///< only when --feature-noise was given
  int beacon_filter = -1;          ///< -1: the world's recipe
  double play_consistency = 0.0;   ///< only when --play-consistency was given
  double nll_min_std = 0.0;        ///< only when --nll-min-std was given
  double gripper_min_std = 0.0;    ///< only when --gripper-min-std was given
  double weight_decay = 0.0;       ///< only when --weight-decay was given
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

/// A world's experiment defaults: the paper's protocol for it.
struct WorldDefaults {
  int runs = 15;
  int tests = 100;
  std::vector<int> demos = {10};
};

/// The worlds `recon experiment` runs, in the order `--help` lists them.
const std::vector<std::string>& ExperimentWorlds();
/// The protocol of `world` (one of ExperimentWorlds()).
WorldDefaults DefaultsOf(const std::string& world);
/// What `world`'s experiment is, for `--help`.
std::string ExperimentHelp(const std::string& world);

/// out/<world>-<local date and time>: where an experiment goes without --out.
std::string DefaultOutDir(const std::string& world);

/// The experiment `flags` ask for, with the world's recipe where an option was not given
/// (`command` says which were).
experiments::ExperimentConfig ToConfig(const ExperimentFlags& flags, const CLI::App& command);

}  // namespace recon::cli
