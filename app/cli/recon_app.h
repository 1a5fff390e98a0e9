#pragma once

// Every `recon` subcommand and option, on one CLI::App: the program (recon_main.cc) runs it, and
// tests walk it (e.g. to find every numeric option and check that each is range-checked).

#include <CLI/CLI.hpp>

#include "app/cli/experiment_command.h"

namespace recon::cli {

/// Adds the global options and every subcommand of `recon` to `app`. `global` must outlive it.
void BuildReconApp(CLI::App& app, GlobalOptions& global);

}  // namespace recon::cli
