#pragma once

#include <stdexcept>
#include <string>

namespace recon {

/// An error caused by what the user gave us (a file, a flag, a field), as opposed to a broken
/// invariant. The message names the offending file/line/field so the user can fix it; the CLI
/// prints it and exits with status 2 without touching anything already saved.
class UserError : public std::runtime_error {
 public:
  explicit UserError(const std::string& message) : std::runtime_error(message) {}
};

/// Training diverged (a NaN or infinite loss). Carries the step so the caller can report it.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(const std::string& message, int step)
      : std::runtime_error(message), step_(step) {}
  int step() const { return step_; }

 private:
  int step_;
};

}  // namespace recon
