#pragma once

// Starting `recon` as a child process that a test can kill, and counting what a killed writer
// left behind. RECON_CLI is the binary's path (a compile definition of the test).

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace recon::testing {

/// Starts `recon` with `args` (output discarded) and returns its pid.
inline pid_t SpawnRecon(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    std::vector<char*> argv = {const_cast<char*>(RECON_CLI)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(RECON_CLI, argv.data());
    _exit(127);
  }
  return pid;
}

/// Whether the child `pid` has ended, without reaping it: its pid stays the child's until the
/// test's own kill and waitpid, so a kill can never reach a process that reused the number.
inline bool HasEnded(pid_t pid) {
  siginfo_t info{};
  return waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
         info.si_pid == pid;
}

/// Counts files that a killed writer left half-written (they carry ".tmp." in their names).
inline int TemporaryFiles(const std::filesystem::path& dir) {
  int count = 0;
  if (!std::filesystem::exists(dir)) return 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    count += entry.path().filename().string().find(".tmp.") != std::string::npos;
  }
  return count;
}

}  // namespace recon::testing
