#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon session info|episodes|delete-episode|mark|split|export|import`.
void AddSessionCommands(CLI::App& app);

}  // namespace recon::cli
