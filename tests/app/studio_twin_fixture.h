#pragma once

// The studio's tests on a digital twin (tests/app/twin_rig.h): a rig per test, the studio's
// options on its profile, and waiting for what the controller's snapshot shows.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <thread>

#include "app/studio/studio_controller.h"
#include "tests/app/twin_rig.h"

namespace recon::studio::testing {

/// The first snapshot for which `done` holds; a test failure naming the status, the calibration
/// prompt and the last error after `timeout_s`.
inline ui::StudioSnapshot WaitFor(const StudioController& controller,
                                  const std::function<bool(const ui::StudioSnapshot&)>& done,
                                  double timeout_s = 30) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    ui::StudioSnapshot s = controller.Snapshot();
    if (done(s)) return s;
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "timed out; status: " << s.status
                    << "; prompt: " << (s.calibration.guided ? s.calibration.guided->prompt : "")
                    << (s.errors.empty() ? "" : "; last error: " + s.errors.back());
      return s;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

/// A twin rig in a fresh temporary folder, and the studio's options on its profile.
class StudioTwinCellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/recon-studio-twin-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
    rig_ = std::make_unique<testing::TwinRig>(dir_ / "twin");
  }
  void TearDown() override {
    rig_.reset();
    std::filesystem::remove_all(dir_);
  }

  StudioOptions Options() const {
    StudioOptions options;
    options.session_dir = (dir_ / "session").string();
    options.recent_sessions_file = (dir_ / "recent.json").string();
    options.cell_profile = rig_->profile;
    options.dev_dir = (dir_ / "no-dev").string();
    options.calibration_points = 5;
    options.countdown_s = 0;
    return options;
  }

  std::filesystem::path dir_;
  std::unique_ptr<testing::TwinRig> rig_;
};

}  // namespace recon::studio::testing
