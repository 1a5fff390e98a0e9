#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon uwb monitor (--port PATH ... | --fake N) [--mode lec|tlv] [--name ID=NAME ...]
/// [--count N] [--seconds S] [--json]`: one line per reading of each DWM1001 tag (several ports
/// at once, or N built-in fake tags), unplugs and reconnections on stderr, and the counts per
/// port at the end.
void AddUwbCommand(CLI::App& app);

}  // namespace recon::cli
