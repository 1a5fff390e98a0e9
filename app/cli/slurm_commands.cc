#include "app/cli/slurm_commands.h"

#include <cstdio>
#include <filesystem>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/option_checks.h"
#include "app/cli/subprocess.h"
#include "app/cli/sweep_commands.h"
#include "engine/core/digest.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/experiments/sweep_plan.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

struct SubmitFlags {
  std::string dir;
  bool slurm = false;
  std::string partition, time;
  int cpus_per_task = 1;
  int max_parallel = 0;  ///< 0: as many as the cluster gives
  bool dry_run = false;
};

/// The job name of the sweep in `dir`: every task of every submission carries it, so the queue
/// is asked for this sweep's tasks alone.
std::string JobName(const std::string& dir) {
  return "recon-" + DigestHex(Fnv1a(fs::absolute(dir).lexically_normal().string())).substr(0, 8);
}

std::string Quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// "0-3,5,7-9": the indices (sorted) as Slurm's --array takes them.
std::string ArraySpec(const std::vector<int>& indices) {
  std::string spec;
  for (size_t i = 0; i < indices.size();) {
    size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    spec += (spec.empty() ? "" : ",") + std::to_string(indices[i]);
    if (j > i) spec += "-" + std::to_string(indices[j]);
    i = j + 1;
  }
  return spec;
}

/// Unit index -> its task's state letters ("PD", "R", "CG", ...) for the tasks of the sweep in
/// `dir` still in the queue; none when the queue cannot be read, with `why` said.
std::optional<std::map<int, std::string>> QueuedUnits(const std::string& dir, std::string& why) {
  if (!OnPath("squeue")) {
    why = "no squeue on PATH";
    return std::nullopt;
  }
  const ProgramResult r = RunProgram({"squeue", "-h", "-r", "-n", JobName(dir), "-o", "%i %t"});
  if (r.exit_code != 0) {
    why = "squeue failed: " + r.err.substr(0, r.err.find('\n'));
    return std::nullopt;
  }
  std::map<int, std::string> queued;
  std::istringstream lines(r.out);
  for (std::string id, state; lines >> id >> state;) {
    const size_t underscore = id.find('_');
    if (underscore == std::string::npos) continue;
    try {
      queued[std::stoi(id.substr(underscore + 1))] = state;
    } catch (const std::exception&) {
      // "123_[4-7]": tasks not yet split out of a pending array are read from the range.
      int first = 0, last = 0;
      if (std::sscanf(id.c_str() + underscore + 1, "[%d-%d", &first, &last) == 2) {
        for (int k = first; k <= last; ++k) queued[k] = state;
      }
    }
  }
  return queued;
}

/// The units of the plan in `dir` that are done (a whole unit file), in plan order.
std::vector<bool> DoneUnits(const std::string& dir, size_t count) {
  std::vector<bool> done(count, false);
  for (size_t k = 0; k < count; ++k) {
    try {
      done[k] = experiments::ReadUnitResult(dir, static_cast<int>(k)).has_value();
    } catch (const UserError&) {
      done[k] = false;  // damaged: to be run again
    }
  }
  return done;
}

/// The last line of `text` that says something (a cancelled task's log ends in slurmstepd's
/// "*** JOB 12 ON node CANCELLED AT ... ***", a failed unit's in recon's error), cut to a line.
std::string LastWords(const std::string& text) {
  std::istringstream lines(text);
  std::string last;
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  constexpr size_t kMaxChars = 160;
  if (last.size() > kMaxChars) last = last.substr(0, kMaxChars - 3) + "...";
  return last;
}

/// The submissions recorded in DIR/slurm/jobs.json (a JSON array; empty when there were none
/// or the file is damaged, which loses only history: the units then read as missing).
json ReadSubmissions(const fs::path& slurm) {
  try {
    const std::optional<std::string> text = ReadWholeFile((slurm / "jobs.json").string());
    if (!text) return json::array();
    json jobs = json::parse(*text);
    if (jobs.is_array()) return jobs;
  } catch (const json::exception&) {
  } catch (const UserError&) {
  }
  return json::array();
}

/// Where array task `unit` of `job` logs (the script's --output=task_%A_%a.log).
fs::path TaskLog(const fs::path& slurm, const std::string& job, int unit) {
  return slurm / ("task_" + job + "_" + std::to_string(unit) + ".log");
}

/// Unit index -> the job of the latest submission that had it.
std::map<int, std::string> SubmittedUnits(const fs::path& slurm) {
  std::map<int, std::string> submitted;
  for (const json& submission : ReadSubmissions(slurm)) {
    if (!submission.is_object() || !submission.contains("job") || !submission.contains("units") ||
        !submission["units"].is_array()) {
      continue;
    }
    const std::string job = submission["job"].is_string() ? submission["job"].get<std::string>()
                                                          : submission["job"].dump();
    for (const json& unit : submission["units"]) {
      if (unit.is_number_integer()) submitted[unit.get<int>()] = job;
    }
  }
  return submitted;
}

/// Why unit `unit` of `job` ended without a result: the last words of its task's log. Read
/// from the logs, not from accounting (sacct), which many clusters and the one-node cluster
/// do not keep.
std::string WhyItFailed(const fs::path& slurm, const std::string& job, int unit) {
  std::optional<std::string> log;
  try {
    log = ReadWholeFile(TaskLog(slurm, job, unit).string());
  } catch (const UserError& e) {
    return e.what();
  }
  if (!log) return "no log: cancelled or refused before it started";
  const std::string words = LastWords(*log);
  return words.empty() ? "its log is empty" : words;
}

/// The sweep folder's absolute path, refused when a job script cannot carry it: a line break
/// would end the script's line (and the rest would run as a command), and '%' is one of
/// Slurm's file-name patterns (%j, %A), which would rename the logs.
std::string SubmittableFolder(const std::string& dir_argument) {
  const std::string dir = fs::absolute(dir_argument).lexically_normal().string();
  for (const char c : dir) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '%') {
      throw UserError("the sweep folder " + dir_argument + " cannot be submitted: its path holds " +
                      (c == '%' ? std::string("a '%', which Slurm reads as a file-name pattern")
                                : std::string("a line break or another control character")) +
                      "; move it to a path without one; nothing was submitted");
    }
  }
  return dir;
}

/// sbatch's command line for `script_path`: the log path goes here, not into the script.
std::vector<std::string> SbatchArguments(const std::string& dir, const std::string& script_path) {
  return {"sbatch", "--parsable", "--output=" + dir + "/slurm/task_%A_%a.log", script_path};
}

/// The job script of `units` of the sweep in `dir` (its SubmittableFolder).
std::string ArrayScript(const SubmitFlags& flags, const std::string& dir,
                        const std::vector<int>& units) {
  const std::string recon = fs::read_symlink("/proc/self/exe").string();
  std::string script =
      "#!/bin/bash\n# A RECON Studio sweep's units as a Slurm job array "
      "(recon experiment submit).\n";
  script += "#SBATCH --job-name=" + JobName(flags.dir) + "\n";
  script += "#SBATCH --array=" + ArraySpec(units) +
            (flags.max_parallel > 0 ? "%" + std::to_string(flags.max_parallel) : "") + "\n";
  script += "#SBATCH --cpus-per-task=" + std::to_string(flags.cpus_per_task) + "\n";
  // The log path is given to sbatch on its command line (SbatchArguments), where any path
  // arrives whole; a directive line would split it at a space.
  script +=
      "# Each task logs to slurm/task_<job>_<task>.log (sbatch --output, given on its "
      "command line).\n";
  if (!flags.time.empty()) script += "#SBATCH --time=" + flags.time + "\n";
  if (!flags.partition.empty()) script += "#SBATCH --partition=" + flags.partition + "\n";
  script += "set -eu\n";
  script += "exec " + Quoted(recon) + " --threads " + std::to_string(flags.cpus_per_task) +
            " experiment run-unit " + Quoted(dir) + " --unit \"$SLURM_ARRAY_TASK_ID\"\n";
  return script;
}

void Submit(const SubmitFlags& flags) {
  if (!flags.slurm) throw UserError("submit needs a scheduler: --slurm");
  if (!flags.dry_run && !OnPath("sbatch")) {
    throw UserError(
        "no sbatch on PATH: submit from a Slurm login node (or start one here with "
        "scripts/slurm-local up DIR and export SLURM_CONF); nothing was submitted");
  }
  const experiments::SweepPlan plan = experiments::ReadSweepPlan(flags.dir);
  ConfigOfArguments(plan.arguments);  // a plan this binary can run
  const std::vector<bool> done = DoneUnits(flags.dir, plan.units.size());
  std::string why;
  const std::optional<std::map<int, std::string>> queued = QueuedUnits(flags.dir, why);
  if (!queued && !flags.dry_run) {
    // Without the queue, units still running would be submitted twice.
    throw UserError("cannot read the cluster's queue (" + why + "); nothing was submitted");
  }
  std::vector<int> todo;
  int done_count = 0;
  for (size_t k = 0; k < plan.units.size(); ++k) {
    if (done[k]) {
      ++done_count;
    } else if (!queued || !queued->count(static_cast<int>(k))) {
      todo.push_back(static_cast<int>(k));
    }
  }
  if (todo.empty()) {
    std::printf(
        "nothing to submit: %d of %zu units done, the rest queued (`recon experiment "
        "status %s`)\n",
        done_count, plan.units.size(), flags.dir.c_str());
    return;
  }
  const std::string dir = SubmittableFolder(flags.dir);
  const std::string script = ArrayScript(flags, dir, todo);
  if (flags.dry_run) {
    std::string command;
    for (const std::string& word : SbatchArguments(dir, "SCRIPT")) {
      command += (command.empty() ? "" : " ") + Quoted(word);
    }
    // The script first (sbatch wants "#!" on its first line), then how it would be submitted.
    std::printf("%s# submit with: %s\n", script.c_str(), command.c_str());
    return;
  }
  const fs::path slurm = fs::path(flags.dir) / "slurm";
  EnsureWritableDirectory(slurm.string());
  int submission = 1;
  while (fs::exists(slurm / ("array_" + std::to_string(submission) + ".sbatch"))) ++submission;
  const fs::path script_path = slurm / ("array_" + std::to_string(submission) + ".sbatch");
  WriteFileAtomically(script_path.string(), script);
  const ProgramResult r = RunProgram(SbatchArguments(dir, script_path.string()));
  if (r.exit_code != 0) {
    std::error_code ignored;
    fs::remove(script_path, ignored);
    throw UserError("the cluster refused the job (sbatch exit " + std::to_string(r.exit_code) +
                    "): " + r.err + "nothing was submitted");
  }
  const std::string job = r.out.substr(0, r.out.find_first_of(";\n"));
  // The submissions so far, for people and for `status`.
  const fs::path jobs_path = slurm / "jobs.json";
  json jobs = ReadSubmissions(slurm);
  jobs.push_back({{"job", job}, {"units", todo}, {"script", script_path.filename().string()}});
  WriteFileAtomically(jobs_path.string(), jobs.dump(1) + "\n");
  std::printf(
      "submitted job %s: %zu unit(s) (%s) as an array%s; follow it with `recon "
      "experiment status %s`, then `recon experiment collect %s`\n",
      job.c_str(), todo.size(), ArraySpec(todo).c_str(),
      done_count > 0 ? (" (" + std::to_string(done_count) + " done before)").c_str() : "",
      flags.dir.c_str(), flags.dir.c_str());
}

void Status(const std::string& dir) {
  const experiments::SweepPlan plan = experiments::ReadSweepPlan(dir);
  const std::vector<bool> done = DoneUnits(dir, plan.units.size());
  std::string why;
  const std::optional<std::map<int, std::string>> queued = QueuedUnits(dir, why);
  const fs::path slurm = fs::path(dir) / "slurm";
  const std::map<int, std::string> submitted = SubmittedUnits(slurm);
  std::vector<int> running, pending, failed, missing;
  int done_count = 0;
  for (size_t k = 0; k < plan.units.size(); ++k) {
    const int unit = static_cast<int>(k);
    if (done[k]) {
      ++done_count;
    } else if (queued && queued->count(unit)) {
      (queued->at(unit) == "PD" ? pending : running).push_back(unit);
    } else if (queued && submitted.count(unit)) {
      failed.push_back(unit);  // it ran, or was meant to, and left no result
    } else {
      missing.push_back(unit);
    }
  }
  std::printf("%zu units: %d done, %zu running, %zu pending, %zu failed, %zu missing%s\n",
              plan.units.size(), done_count, running.size(), pending.size(), failed.size(),
              missing.size(), queued ? "" : (" (" + why + ": from the unit files alone)").c_str());
  if (!running.empty()) std::printf("running: %s\n", ArraySpec(running).c_str());
  if (!pending.empty()) std::printf("pending: %s\n", ArraySpec(pending).c_str());
  if (!failed.empty()) {
    std::printf("failed (submitted, ended without a result): %s\n", ArraySpec(failed).c_str());
    constexpr size_t kShown = 10;
    for (size_t i = 0; i < failed.size() && i < kShown; ++i) {
      const std::string& job = submitted.at(failed[i]);
      std::printf("  unit %d, job %s_%d: %s\n", failed[i], job.c_str(), failed[i],
                  WhyItFailed(slurm, job, failed[i]).c_str());
    }
    if (failed.size() > kShown) {
      std::printf("  and %zu more (their logs: %s/slurm/task_JOB_UNIT.log)\n",
                  failed.size() - kShown, dir.c_str());
    }
  }
  if (!missing.empty()) {
    std::printf("missing (not done and not queued%s): %s\n",
                queued ? ", never submitted" : ": never submitted, failed, killed or preempted",
                ArraySpec(missing).c_str());
  }
  if (!failed.empty() || !missing.empty()) {
    std::printf("`recon experiment submit %s --slurm` runs the %s\n", dir.c_str(),
                failed.empty()    ? "missing"
                : missing.empty() ? "failed"
                                  : "failed and the missing");
  }
}

}  // namespace

void AddSlurmCommands(CLI::App& experiment) {
  // The array's tasks set their own threads (--cpus-per-task).
  auto flags = std::make_shared<SubmitFlags>();
  CLI::App* submit = experiment.add_subcommand(
      "submit",
      "submit a planned sweep's units that are neither done nor queued as one Slurm "
      "job array (DIR must be on a file system every node sees)");
  submit->add_option("dir", flags->dir, "the sweep's folder (its plan.json)")->required();
  submit->add_flag("--slurm", flags->slurm, "submit to Slurm (sbatch)")->required();
  // Both go into the job script's #SBATCH lines: only what Slurm accepts there, so that no
  // value can end a line and add a command to the script.
  submit->add_option("--partition", flags->partition, "the partition (default: the cluster's)")
      ->check([](const std::string& value) -> std::string {
        static const std::regex kPartitions("[A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*");
        return std::regex_match(value, kPartitions)
                   ? ""
                   : "a partition name (letters, digits, '_', '.', '-'; several joined by ',')";
      });
  submit->add_option("--time", flags->time, "each task's time limit, as sbatch takes it")
      ->check([](const std::string& value) -> std::string {
        static const std::regex kTime("([0-9]+-)?[0-9]+(:[0-9]+){0,2}|UNLIMITED|INFINITE");
        return std::regex_match(value, kTime)
                   ? ""
                   : "a time limit as sbatch takes it: minutes, minutes:seconds, "
                     "hours:minutes:seconds, days-hours, days-hours:minutes or "
                     "days-hours:minutes:seconds";
      });
  submit->add_option("--cpus-per-task", flags->cpus_per_task, "cores per unit (its threads)")
      ->check(WholeBetween(1, 256))
      ->capture_default_str();
  submit->add_option("--max-parallel", flags->max_parallel, "units running at once, at most")
      ->check(WholeBetween(1, 100000));
  submit->add_flag("--dry-run", flags->dry_run, "print the sbatch script, submit nothing");
  submit->callback([flags] { Submit(*flags); });

  auto status_dir = std::make_shared<std::string>();
  CLI::App* status = experiment.add_subcommand(
      "status",
      "how far a sweep is: units done (their files), running and pending (squeue), failed "
      "(submitted, no result: why, from its task's log) and missing (never submitted)");
  status->add_option("dir", *status_dir, "the sweep's folder (its plan.json)")->required();
  status->callback([status_dir] { Status(*status_dir); });
}

}  // namespace recon::cli
