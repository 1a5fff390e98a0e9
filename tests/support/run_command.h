#pragma once

// Runs a command line as a user would type it, for tests of the real binaries and tools.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace recon::testing {

struct CommandResult {
  int exit_code;       ///< -1 if the command did not exit normally
  std::string output;  ///< stdout and stderr together
};

/// Runs `command_line` through the shell with stderr joined to stdout.
inline CommandResult RunCommand(const std::string& command_line) {
  FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace recon::testing
