#include "app/cli/crash_report.h"

#include <execinfo.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include <array>

namespace recon::cli {

namespace {

const char* crash_program = "recon";
constexpr std::array<int, 5> kFatalSignals = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

void Write(const char* text) {
  // write(2) only: the handler runs wherever the crash happened, perhaps inside malloc.
  ssize_t ignored = ::write(STDERR_FILENO, text, strlen(text));
  (void)ignored;
}

void OnFatalSignal(int signal_number) {
  Write("\n");
  Write(crash_program);
  Write(": crashed (");
  Write(sigabbrev_np(signal_number) != nullptr ? sigabbrev_np(signal_number) : "signal");
  Write(", ");
  Write(sigdescr_np(signal_number) != nullptr ? sigdescr_np(signal_number) : "unknown");
  Write(
      "); the stack of the thread that crashed (addr2line -e <binary> <offset> names the "
      "lines):\n");
  void* frames[64];
  const int count = backtrace(frames, 64);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // Die of the same signal, as the program would have without this handler.
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

}  // namespace

void InstallCrashReport(const char* program) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // The sanitizers' own handlers report more (and ours would replace them).
  (void)program;
  return;
#endif
  crash_program = program;
  // backtrace() loads libgcc on its first call, which allocates: do it now, not in the handler.
  void* warm_up[1];
  backtrace(warm_up, 1);
  struct sigaction action {};
  action.sa_handler = OnFatalSignal;
  sigemptyset(&action.sa_mask);
  // A stack of its own on this (the main) thread, so that a stack overflow is reported too.
  static std::array<char, 64 * 1024> alternate_stack;
  stack_t stack{};
  stack.ss_sp = alternate_stack.data();
  stack.ss_size = alternate_stack.size();
  sigaltstack(&stack, nullptr);
  // SA_RESETHAND: a crash inside the handler ends the process instead of looping.
  action.sa_flags = SA_RESETHAND | SA_ONSTACK;
  for (const int signal_number : kFatalSignals) sigaction(signal_number, &action, nullptr);
}

}  // namespace recon::cli
