#pragma once

// The rule every `--out` of recon follows before anything runs: a session folder is written only
// through its session (so an export can never land on an episode, a manifest or a checkpoint),
// and an existing file is replaced only when the user says so with --force.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace recon::cli {

/// The session folder `path` is inside (or is), if any: the nearest ancestor holding a
/// session.json.
std::optional<std::string> EnclosingSession(const std::string& path);

/// UserError, naming `option` and the path, when `path` lies inside a session folder, is an
/// existing folder, or is an existing file and `force` is false. Nothing is written.
void CheckOutputFile(const std::string& option, const std::string& path, bool force);

/// The same for an output folder (a report, an experiment's results): refused inside a session
/// unless it is `allowed_inside` (a session's own report folder), and when it already holds
/// files but not `marker` (the file that says this kind of output was written there before:
/// "report.html", "summary.json"), unless `force`.
void CheckOutputFolder(const std::string& option, const std::string& path, bool force,
                       const std::string& marker, const std::string& allowed_inside = "");

/// Adds `--force` ("replace an existing output file") to `command`.
void AddForceFlag(CLI::App& command, bool& force);

}  // namespace recon::cli
