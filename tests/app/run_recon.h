#pragma once

// Runs the real `recon` binary (RECON_CLI, set by CMake) as a user would, for the CLI tests.

#include <string>

#include "tests/support/run_command.h"

namespace recon::testing {

inline CommandResult RunRecon(const std::string& args) {
  return RunCommand(std::string(RECON_CLI) + " " + args);
}

}  // namespace recon::testing
