#pragma once

#include <CLI/CLI.hpp>

#include "app/cli/experiment_command.h"

namespace recon::cli {

/// Adds `recon train --session DIR` and `recon eval --session DIR`: train RECON and the Baseline
/// on a recorded session and roll the trained policies out with the beacons removed.
void AddTrainCommands(CLI::App& app, const GlobalOptions& global);

}  // namespace recon::cli
