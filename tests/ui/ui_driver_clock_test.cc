// The driver on a SteppedClock: each frame moves the studio's time by one frame step, only after
// the application took in what the frame sent, and waits until the application caught up. What
// a script (and its scripted person) does then depends on frames, not on the machine's speed.

#include <gtest/gtest.h>
#include <imgui.h>

#include <chrono>
#include <memory>
#include <vector>

#include "engine/core/stepped_clock.h"
#include "ui/platform/headless_window.h"
#include "ui/testing/ui_driver.h"

namespace recon::ui {
namespace {

using Ms = std::chrono::milliseconds;

struct ClockedDriver {
  HeadlessWindow window{{320, 200, 16.0f, 1.0f}};
  std::shared_ptr<SteppedClock> clock = std::make_shared<SteppedClock>();
  const SteppedClock::time_point start = clock->Now();
  int frames = 0;
  int settled_checks = 0;
  int refusals_left = 0;  ///< how many times caught_up still says no before yes
  std::vector<SteppedClock::time_point> asked;  ///< the times caught_up was asked about
  UiDriver driver{window, [this] {
                    ++frames;
                    ImGui::Begin("clocked");
                    ImGui::TextUnformatted("a frame");
                    ImGui::End();
                  }};

  ClockedDriver() {
    driver.SetSettledCheck([this] {
      ++settled_checks;
      return true;
    });
    driver.SetClock(clock, [this](SteppedClock::time_point t) {
      asked.push_back(t);
      if (refusals_left > 0) {
        --refusals_left;
        return false;
      }
      return true;
    });
  }
  Ms Elapsed() const { return std::chrono::duration_cast<Ms>(clock->Now() - start); }
};

TEST(UiDriverClockTest, EachFrameMovesTheClockOneStepAndWaitsForTheApplication) {
  ClockedDriver d;
  d.driver.WaitFrames(3);
  EXPECT_EQ(d.frames, 3);
  EXPECT_EQ(d.Elapsed(), 3 * UiDriver::kFrameStep);
  ASSERT_EQ(d.asked.size(), 3u);
  EXPECT_EQ(d.asked[0], d.start + UiDriver::kFrameStep) << "asked about the time moved to";
  EXPECT_GE(d.settled_checks, 3) << "each frame's commands are taken in before time moves";

  // An application still busy with the new time holds the next frame back.
  d.refusals_left = 4;
  d.asked.clear();
  d.driver.WaitFrames(1);
  EXPECT_EQ(d.asked.size(), 5u);
  EXPECT_EQ(d.Elapsed(), 4 * UiDriver::kFrameStep);
}

TEST(UiDriverClockTest, HoldingAKeyLastsItsTimeOnTheClockInFrames) {
  ClockedDriver d;
  d.driver.Hold(ImGuiKey_Space, 0.1);
  // 0.1 s held is five frames of 20 ms, then one frame released and two to show its effect,
  // however long each frame took to draw.
  EXPECT_EQ(d.frames, 8);
  EXPECT_EQ(d.Elapsed(), Ms(160));
}

}  // namespace
}  // namespace recon::ui
