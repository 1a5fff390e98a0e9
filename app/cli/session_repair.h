#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon session repair DIR --world W [...]` under `session`: gives a session folder that
/// lost its session.json a new manifest, built as `recon record` builds a new session's from
/// the same options and checked against every episode file before it is written.
void AddSessionRepairCommand(CLI::App& session);

}  // namespace recon::cli
