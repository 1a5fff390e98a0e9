// The studio closed while a training runs (the window's close button answered "stop and
// close", or the process killed): the session, opened again, says its training was cut short,
// until a training ends there.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <thread>

#include "app/studio/studio_controller.h"
#include "tests/app/controller_wait.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;

class StudioCloseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("recon-close-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  StudioOptions Options(int train_steps) const {
    StudioOptions options;
    options.session_dir = (dir_ / "session").string();
    options.recent_sessions_file = (dir_ / "config" / "recent.json").string();
    options.real_time = false;
    options.countdown_s = 0;
    options.train_steps = train_steps;
    return options;
  }

  static ui::StudioSnapshot WaitFor(const StudioController& controller,
                                    const std::function<bool(const ui::StudioSnapshot&)>& done) {
    return testing::WaitForSnapshot(controller, done, 120);
  }

  fs::path dir_;
};

TEST_F(StudioCloseTest, ATrainingCutShortByClosingIsSaidWhenTheSessionOpensAgain) {
  {
    StudioController controller(Options(1000000));  // far more steps than the test waits for
    controller.Push(ui::StartRecording{});          // the scripted teacher
    const ui::StudioSnapshot recorded =
        WaitFor(controller, [](const auto& s) { return !s.recording && s.episodes.size() == 1; });
    // One of the tabletop's four: the step list does not point to Train yet (what it points to
    // instead, session_view_test.cc checks).
    EXPECT_NE(recorded.next_step, teach::Step::kTrain);
    controller.Push(ui::StartTraining{{"baseline", "recon"}});
    const ui::StudioSnapshot training = WaitFor(controller, [](const auto& s) {
      return s.training_running && !s.training.empty() && s.training[0].step > 0;
    });
    EXPECT_EQ(training.training_cut_short, "") << "a running training is not cut short";
  }  // the studio closes: its controller stops the training
  {
    StudioController controller(Options(20));
    ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) { return now.session_open; });
    EXPECT_NE(s.training_cut_short.find("cut short when the studio closed"), std::string::npos)
        << s.training_cut_short;
    EXPECT_NE(s.training_cut_short.find("Baseline and RECON"), std::string::npos)
        << s.training_cut_short;
    EXPECT_NE(s.status.find("cut short"), std::string::npos) << s.status;
    // A training that ends here, however, is not.
    controller.Push(ui::StartTraining{{"baseline", "recon"}});
    WaitFor(controller, [](const auto& now) { return now.training_running; });
    s = WaitFor(controller, [](const auto& now) { return !now.training_running; });
    EXPECT_EQ(s.training_cut_short, "");
  }
  StudioController reopened(Options(20));
  const ui::StudioSnapshot s = WaitFor(reopened, [](const auto& now) { return now.session_open; });
  EXPECT_EQ(s.training_cut_short, "");
}

}  // namespace
}  // namespace recon::studio
