#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds the simulated cell's commands to `app`: `recon render` (one camera image of a scene)
/// and `recon calibrate --sim` (UWB against AprilTag calibration in the simulated cell).
void AddCellCommands(CLI::App& app);

}  // namespace recon::cli
