#pragma once

// A planned sweep (sweep_commands.h) on a Slurm cluster: its units as one job array, and what
// the cluster and the unit files say of them.
//
//   recon experiment submit DIR --slurm [--partition P] [--time T] [--cpus-per-task N]
//                               [--max-parallel M] [--dry-run]
//   recon experiment status DIR
//
// Status reads the unit files, the queue (squeue) and each submission's task logs: a unit
// submitted that is neither done nor queued failed (cancelled, preempted, out of time, or an
// error of its own), and its log's last words say which. Submitting again submits only the
// units neither done nor queued: the missing and the failed.

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon experiment submit` and `recon experiment status`.
void AddSlurmCommands(CLI::App& experiment);

}  // namespace recon::cli
