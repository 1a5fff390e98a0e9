#pragma once

// An experiment as a plan of independent units (engine/experiments/sweep_plan.h), run the same
// way on this machine's cores and as a cluster's job array:
//
//   recon experiment <world> ... --plan-only --out DIR   the plan, nothing trained
//   recon experiment run-unit DIR --unit K               unit K, its result into DIR/units/
//   recon experiment collect DIR                         whatever is done, into results.csv,
//                                                        summary.json and the figures
//
// `recon experiment <world> ... --out DIR` is those three steps on the local cores.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/experiment_command.h"
#include "app/cli/experiment_flags.h"
#include "engine/experiments/sweep_plan.h"

namespace recon::cli {

/// Adds `world`'s experiment subcommand and its options to `experiment`, filling `flags`; no
/// callback (experiment_command.cc).
CLI::App* AddWorldOptions(CLI::App& experiment, const std::string& world, const std::string& help,
                          const std::shared_ptr<ExperimentFlags>& flags);

/// What of `command_line` (a `recon [--threads N] experiment <world> ...` line) a plan keeps:
/// from the world on, without --out, --force, --plan-only and --jobs, which change where and
/// how fast the units run, never what they compute.
std::vector<std::string> SweepArguments(const std::vector<std::string>& command_line);

/// The experiment a plan's `arguments` ask for, parsed as the command line parses them.
/// UserError naming the argument for one this binary does not know.
experiments::ExperimentConfig ConfigOfArguments(const std::vector<std::string>& arguments);

/// Writes `config`'s plan into `dir`, or keeps the plan already there when it is the same
/// (the units done are kept: a killed local run resumes). UserError for another sweep's plan
/// unless `force` (which removes its units).
experiments::SweepPlan PlanSweep(const experiments::ExperimentConfig& config,
                                 const std::vector<std::string>& arguments, const std::string& dir,
                                 bool force);

/// Runs every unit of `plan` not done yet, `jobs` at a time, each result written as it ends;
/// `on_done` sees each (serialised).
void RunUnitsLocally(const experiments::ExperimentConfig& config,
                     const experiments::SweepPlan& plan, const std::string& dir, int jobs,
                     const std::function<void(const experiments::UnitResult&)>& on_done);

/// Gathers the units done into results.csv, summary.json and the figures; returns the missing
/// units' indices (none written when no unit is done: UserError).
std::vector<int> CollectSweep(const std::string& dir, bool print_table);

/// Adds `recon experiment run-unit` and `recon experiment collect`.
void AddSweepCommands(CLI::App& experiment, const GlobalOptions& global);

}  // namespace recon::cli
