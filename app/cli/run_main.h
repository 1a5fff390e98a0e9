#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace recon::cli {

/// Parses the command line and runs `run` afterwards (commands that run from CLI11 callbacks
/// need none), turning errors into exit codes the same way in every program: 0 for --help and
/// --version, 2 for usage errors and UserError ("<program>: error: <message>" on stderr, nothing
/// saved is touched), 1 for anything else ("internal error").
int RunMain(CLI::App& app, int argc, char** argv, const char* program,
            const std::function<void()>& run = {});

/// The command line RunMain was given, after the program's name (for commands that keep how
/// they were asked for, e.g. an experiment's plan).
const std::vector<std::string>& CommandLine();

}  // namespace recon::cli
