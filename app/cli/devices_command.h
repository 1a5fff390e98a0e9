#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon devices list`: the beacons, cameras, gamepads and robots connected now.
void AddDevicesCommand(CLI::App& app);

}  // namespace recon::cli
