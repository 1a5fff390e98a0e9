#pragma once

// An experiment laid out on disk as a plan of independent units, so that any machine that sees
// the folder (this one's cores, or a cluster's nodes over a shared file system) can run any
// unit, and whatever is done can be collected at any time:
//
//   DIR/plan.json          what to run: the experiment's own arguments, every unit with its
//                          seeds, and what the table says of the world and its expert; with a
//                          digest of all of it, so a plan edited by hand is refused
//   DIR/units/unit_K.json  unit K's result, written atomically once it is done: the same bytes
//                          whichever machine ran it or how often (no wall-clock time in it)
//   DIR/units/unit_K.timing.json  how long unit K trained, and where (kept apart for that reason)

#include <optional>
#include <string>
#include <vector>

#include "engine/experiments/experiment.h"

namespace recon::experiments {

/// The version of the plan and unit files; a plan of another is refused.
constexpr int kSweepPlanVersion = 1;

struct SweepPlan {
  int version = kSweepPlanVersion;
  std::string made_by;  ///< the binary that wrote it ("recon 0.1.0")
  /// The experiment subcommand's arguments, world first ("dynamic2d", "--runs", "2", ...),
  /// without --out, --force or --plan-only: every unit is trained from exactly these.
  std::vector<std::string> arguments;
  std::vector<ExperimentUnit> units;
  /// Per unit, its seeds, for people reading the plan (the run derives them again).
  std::vector<uint64_t> data_seeds, train_seeds;
  ExperimentResult described;  ///< DescribeExperiment's answer, so collecting needs no world
};

/// The plan of `config` run as `arguments` (DescribeExperiment runs the expert once).
SweepPlan MakeSweepPlan(const ExperimentConfig& config, std::vector<std::string> arguments,
                        std::string made_by);

std::string PlanPath(const std::string& dir);
std::string UnitPath(const std::string& dir, int index);

/// Writes DIR/plan.json atomically, with its digest.
void WriteSweepPlan(const std::string& dir, const SweepPlan& plan);
/// UserError naming the file and what is wrong: missing, not a plan, of another version, or
/// edited since it was written (its digest).
SweepPlan ReadSweepPlan(const std::string& dir);

/// Writes unit `result`, run from `plan`, into DIR/units/ atomically (the result, then its
/// time beside it). UserError, and nothing written, when DIR/plan.json is no longer `plan`: it
/// was replaced by another sweep (or removed) while the unit ran.
void WriteUnitResult(const std::string& dir, const SweepPlan& plan, const UnitResult& result,
                     double train_seconds, const std::string& host);
/// Unit `index`'s result; none when it is not done. UserError naming the file for one that is
/// damaged (truncated, edited, or of another unit).
std::optional<UnitResult> ReadUnitResult(const std::string& dir, int index);
/// The unit file's bytes as WriteUnitResult writes them (tests compare them).
std::string UnitResultText(const UnitResult& result);

}  // namespace recon::experiments
