#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon record --session DIR --world W ...`: records demonstrations and play data with the
/// scripted teleop in the simulated cell into a session (created on first use, appended after).
void AddRecordCommand(CLI::App& app);

}  // namespace recon::cli
