#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon uwb monitor --port PATH [--count N] [--seconds S] [--json]`: one line per reading
/// of a DWM1001 on a serial port, and what was dropped at the end.
void AddUwbCommand(CLI::App& app);

}  // namespace recon::cli
