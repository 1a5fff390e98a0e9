#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Settings shared by every subcommand (`recon --threads N ...`).
struct GlobalOptions {
  int threads = 1;
};

/// Adds `recon experiment dynamic2d|static2d|bintransfer|tabletop` and the sweep's commands
/// (run-unit, collect) to `app`.
void AddExperimentCommands(CLI::App& app, const GlobalOptions& global);

}  // namespace recon::cli
