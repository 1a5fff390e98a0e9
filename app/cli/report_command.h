#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon report DIR [--out FOLDER] [--episode demo_N]`: the session's HTML report.
void AddReportCommand(CLI::App& app);

}  // namespace recon::cli
