#pragma once

// The message a call gives as a recon::UserError, for tests that compare a refusal's words.

#include <string>

#include "engine/core/error.h"

namespace recon::testing {

/// The message of the UserError that `f()` throws; "" when it throws none. Any other
/// exception passes through, so that the test fails on it with its own message.
template <typename F>
std::string UserErrorOf(F f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

}  // namespace recon::testing
