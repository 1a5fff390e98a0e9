#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "app/studio/studio_controller.h"

namespace recon::studio::testing {

/// Polls the controller's snapshots until `done` holds and the controller has settled; fails the
/// test (and returns the last snapshot) after `timeout_s`, naming the status and the last error.
inline ui::StudioSnapshot WaitForSnapshot(
    const StudioController& controller, const std::function<bool(const ui::StudioSnapshot&)>& done,
    double timeout_s = 60) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    ui::StudioSnapshot s = controller.Snapshot();
    if (done(s) && controller.Settled()) return s;
    if (std::chrono::steady_clock::now() > deadline) {
      std::string training;
      for (const ui::TrainingView& view : s.training) {
        training += "; " + view.label + " at step " + std::to_string(view.step) + " of " +
                    std::to_string(view.steps) + (view.running ? " (running)" : "");
      }
      ADD_FAILURE() << "timed out after " << timeout_s << " s; status: " << s.status << training
                    << (s.errors.empty() ? "" : "; last error: " + s.errors.back());
      return s;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace recon::studio::testing
