#include "app/cli/sweep_commands.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "engine/core/error.h"
#include "engine/experiments/summary.h"
#include "engine/learn/learner.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

constexpr char kMadeBy[] = "recon 0.1.0";

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

std::string HostName() {
  char name[256] = "";
  if (gethostname(name, sizeof(name) - 1) != 0) return "unknown";
  return name;
}

/// The plan in `dir` with the experiment it asks for, checked to be this binary's: the units
/// its arguments give now are the units it lists.
std::pair<experiments::SweepPlan, experiments::ExperimentConfig> OpenPlan(const std::string& dir) {
  experiments::SweepPlan plan = experiments::ReadSweepPlan(dir);
  experiments::ExperimentConfig config = ConfigOfArguments(plan.arguments);
  const std::vector<experiments::ExperimentUnit> units = experiments::PlanUnits(config);
  const auto same = [](const experiments::ExperimentUnit& a, const experiments::ExperimentUnit& b) {
    return a.index == b.index && a.demos == b.demos && a.condition == b.condition && a.run == b.run;
  };
  if (units.size() != plan.units.size() ||
      !std::equal(units.begin(), units.end(), plan.units.begin(), same)) {
    throw UserError(experiments::PlanPath(dir) +
                    " lists other units than its arguments give "
                    "with this recon (" +
                    kMadeBy + "; the plan was made by " + plan.made_by +
                    "): plan the sweep again with this binary");
  }
  return {std::move(plan), std::move(config)};
}

/// The indices `spec` names: "7", "0-9" or "1,4,6-8"; UserError naming what is wrong.
std::vector<int> UnitIndices(const std::vector<std::string>& specs, int count) {
  std::vector<int> indices;
  for (const std::string& spec : specs) {
    int first = 0, last = 0;
    char tail = 0;
    if (std::sscanf(spec.c_str(), "%d-%d%c", &first, &last, &tail) == 2) {
    } else if (std::sscanf(spec.c_str(), "%d%c", &first, &tail) == 1) {
      last = first;
    } else {
      throw UserError("--unit " + spec + ": expected a unit number K or a range A-B");
    }
    if (first < 0 || last >= count || first > last) {
      throw UserError("--unit " + spec + ": the plan's units are 0 to " +
                      std::to_string(count - 1));
    }
    for (int k = first; k <= last; ++k) indices.push_back(k);
  }
  return indices;
}

// A plan no unit has run from and no cluster was given holds no work: a corrected command
// replaces it (the first unit of the plan before may have refused its configuration).
bool NothingOfThePlanRanYet(const std::string& dir) {
  std::error_code error;
  const fs::path units = fs::path(dir) / "units";
  const bool no_units = !fs::exists(units, error) || fs::is_empty(units, error);
  return !error && no_units && !fs::exists(fs::path(dir) / "slurm", error);
}

}  // namespace

std::vector<std::string> SweepArguments(const std::vector<std::string>& command_line) {
  const auto experiment = std::find(command_line.begin(), command_line.end(), "experiment");
  if (experiment == command_line.end()) throw UserError("not an experiment's command line");
  std::vector<std::string> kept;
  for (auto it = experiment + 1; it != command_line.end(); ++it) {
    const std::string& a = *it;
    if (a == "--force" || a == "--plan-only") continue;
    if (a == "--out" || a == "--jobs") {
      if (it + 1 != command_line.end()) ++it;  // and its value
      continue;
    }
    if (a.rfind("--out=", 0) == 0 || a.rfind("--jobs=", 0) == 0) continue;
    kept.push_back(a);
  }
  return kept;
}

experiments::ExperimentConfig ConfigOfArguments(const std::vector<std::string>& arguments) {
  if (arguments.empty()) throw UserError("a plan without arguments");
  const std::string& world = arguments.front();
  const std::vector<std::string>& worlds = ExperimentWorlds();
  if (std::find(worlds.begin(), worlds.end(), world) == worlds.end()) {
    throw UserError("a plan of the unknown experiment \"" + world + "\"");
  }
  CLI::App parser("a sweep's experiment");
  CLI::App* experiment = parser.add_subcommand("experiment");
  auto flags = std::make_shared<ExperimentFlags>();
  CLI::App* command = AddWorldOptions(*experiment, world, "", flags);
  std::vector<std::string> line = {"experiment"};
  line.insert(line.end(), arguments.begin(), arguments.end());
  std::reverse(line.begin(), line.end());  // CLI11 takes them last first
  try {
    parser.parse(line);
  } catch (const CLI::ParseError& e) {
    throw UserError(std::string("the plan's arguments do not parse: ") + e.what());
  }
  return ToConfig(*flags, *command);
}

experiments::SweepPlan PlanSweep(const experiments::ExperimentConfig& config,
                                 const std::vector<std::string>& arguments, const std::string& dir,
                                 bool force) {
  if (fs::exists(experiments::PlanPath(dir))) {
    std::optional<experiments::SweepPlan> existing;
    try {
      existing = experiments::ReadSweepPlan(dir);
    } catch (const UserError&) {
      if (!force) throw;
    }
    if (existing && existing->arguments == arguments) return *existing;  // resume
    if (!force && !NothingOfThePlanRanYet(dir)) {
      throw UserError(dir + " holds the plan of another sweep (" + experiments::PlanPath(dir) +
                      "); choose another --out or pass --force to replace it");
    }
    std::error_code ignored;
    fs::remove_all(fs::path(dir) / "units", ignored);
  }
  experiments::SweepPlan plan = experiments::MakeSweepPlan(config, arguments, kMadeBy);
  experiments::WriteSweepPlan(dir, plan);
  return plan;
}

void RunUnitsLocally(const experiments::ExperimentConfig& config,
                     const experiments::SweepPlan& plan, const std::string& dir, int jobs,
                     const std::function<void(const experiments::UnitResult&)>& on_done) {
  std::vector<experiments::ExperimentUnit> todo;
  for (const experiments::ExperimentUnit& unit : plan.units) {
    std::optional<experiments::UnitResult> done;
    try {
      done = experiments::ReadUnitResult(dir, unit.index);
    } catch (const UserError& e) {
      std::fprintf(stderr, "%s; running it again\n", e.what());  // damaged: run again
    }
    if (done) {
      if (on_done) on_done(*done);
    } else {
      todo.push_back(unit);
    }
  }
  const std::string host = HostName();
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex mutex;
  const auto worker = [&] {
    while (!failed) {
      const size_t i = next++;
      if (i >= todo.size()) return;
      try {
        const auto start = std::chrono::steady_clock::now();
        const experiments::UnitResult result = experiments::RunUnit(config, todo[i]);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        experiments::WriteUnitResult(dir, plan, result, seconds, host);
        std::lock_guard<std::mutex> lock(mutex);
        if (on_done) on_done(result);
      } catch (...) {
        failed = true;
        std::lock_guard<std::mutex> lock(mutex);
        if (!first_error) first_error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> threads;
  const int workers = std::min<int>(std::max(1, jobs), static_cast<int>(todo.size()));
  for (int j = 0; j < workers; ++j) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

std::vector<int> CollectSweep(const std::string& dir, bool print_table) {
  const auto [plan, config] = OpenPlan(dir);
  std::vector<experiments::UnitResult> done;
  std::vector<int> missing;
  for (const experiments::ExperimentUnit& unit : plan.units) {
    std::optional<experiments::UnitResult> result;
    try {
      result = experiments::ReadUnitResult(dir, unit.index);
    } catch (const UserError& e) {
      std::fprintf(stderr, "%s\n", e.what());  // counted as missing: run it again
    }
    if (result) {
      done.push_back(std::move(*result));
    } else {
      missing.push_back(unit.index);
    }
  }
  if (done.empty()) {
    throw UserError("no unit of " + dir + " is done yet (" + std::to_string(plan.units.size()) +
                    " planned): run them with `recon experiment run-unit " + dir +
                    " --unit K`; nothing was written");
  }
  const experiments::ExperimentResult result =
      experiments::AssembleExperiment(config, plan.described, done);
  const std::vector<std::string> written = experiments::WriteExperimentOutputs(config, result, dir);
  if (print_table) PrintTable(experiments::Summarize(config, result), result);
  for (const std::string& path : written) std::printf("wrote %s\n", path.c_str());
  return missing;
}

void AddSweepCommands(CLI::App& experiment, const GlobalOptions& global) {
  struct UnitFlags {
    std::string dir;
    std::vector<std::string> units;
  };
  auto unit_flags = std::make_shared<UnitFlags>();
  CLI::App* run_unit = experiment.add_subcommand(
      "run-unit",
      "train and roll out units of a planned sweep (--plan-only), each result into "
      "DIR/units/ as it ends; a unit already done is left as it is");
  run_unit->add_option("dir", unit_flags->dir, "the sweep's folder (its plan.json)")->required();
  run_unit->add_option("--unit", unit_flags->units, "unit number K, or a range A-B (repeatable)")
      ->required()
      ->delimiter(',');
  run_unit->callback([unit_flags, &global] {
    const auto [plan, config] = OpenPlan(unit_flags->dir);
    learn::SetThreads(global.threads);
    const std::vector<int> indices =
        UnitIndices(unit_flags->units, static_cast<int>(plan.units.size()));
    const std::string host = HostName();
    for (int k : indices) {
      std::optional<experiments::UnitResult> done;
      try {
        done = experiments::ReadUnitResult(unit_flags->dir, k);
      } catch (const UserError& e) {
        std::fprintf(stderr, "%s; running it again\n", e.what());  // a damaged unit is redone
      }
      if (done) {
        std::printf("unit %d is done already (%s)\n", k,
                    experiments::UnitPath(unit_flags->dir, k).c_str());
        continue;
      }
      const auto start = std::chrono::steady_clock::now();
      const experiments::UnitResult result = experiments::RunUnit(config, plan.units[k]);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      experiments::WriteUnitResult(unit_flags->dir, plan, result, seconds, host);
      std::printf("unit %d: %s, %d demos, run %d: metric %.4f (%.1f s; wrote %s)\n", k,
                  result.run.condition.c_str(), result.run.demos, result.run.run, result.run.metric,
                  seconds, experiments::UnitPath(unit_flags->dir, k).c_str());
      std::fflush(stdout);
    }
  });

  auto collect_dir = std::make_shared<std::string>();
  CLI::App* collect = experiment.add_subcommand(
      "collect",
      "gather a sweep's finished units into results.csv, summary.json and the "
      "figures, and say which units are missing");
  collect->add_option("dir", *collect_dir, "the sweep's folder (its plan.json)")->required();
  collect->callback([collect_dir] {
    const std::vector<int> missing = CollectSweep(*collect_dir, true);
    if (missing.empty()) {
      std::printf("every unit is done\n");
      return;
    }
    std::string list;
    for (int k : missing) list += (list.empty() ? "" : ",") + std::to_string(k);
    std::printf(
        "%zu unit(s) missing: %s (run them with `recon experiment run-unit %s --unit K`)"
        "\n",
        missing.size(), list.c_str(), collect_dir->c_str());
  });
}

}  // namespace recon::cli
