#pragma once

// Running another program (Slurm's sbatch, squeue, scancel) and reading what it says.

#include <string>
#include <vector>

namespace recon::cli {

struct ProgramResult {
  int exit_code = 0;  ///< 127 when the program could not be started
  std::string out, err;
};

/// Runs argv[0] (looked up on PATH) with the arguments, stdin closed, and waits for it.
ProgramResult RunProgram(const std::vector<std::string>& argv);

/// Whether `program` is on PATH.
bool OnPath(const std::string& program);

}  // namespace recon::cli
