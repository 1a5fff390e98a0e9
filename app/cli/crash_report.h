#pragma once

// What a program prints when it crashes (a segmentation fault, an abort, an illegal
// instruction): which signal, and the stack of the thread that crashed, before it dies of the
// signal as it would have (so its exit status, 128 + the signal, is unchanged). A crash that
// happens on a user's machine or once in a CI run can then be located from its log alone.

namespace recon::cli {

/// Installs the handlers for `program` (kept, not copied: pass a string literal). Idempotent.
void InstallCrashReport(const char* program);

}  // namespace recon::cli
