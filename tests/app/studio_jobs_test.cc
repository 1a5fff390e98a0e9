// The studio's training job: both methods train on their own threads, and one method's failure
// neither stops the other nor loses its checkpoint.

#include "app/studio/studio_jobs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "app/studio/job_thread.h"
#include "engine/core/error.h"
#include "engine/store/session.h"
#include "tests/app/run_recon.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path RecordedSession(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("recon_studio_jobs_" + name);
  fs::remove_all(dir);
  const testing::CommandResult r = testing::RunRecon("record --session " + dir.string() +
                                                     " --world static2d --demos 4 --play 6");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir;
}

cli::SessionTrainingOptions QuickTraining(const store::Session& session) {
  cli::SessionTrainingOptions options;
  options.steps = 40;
  options.seed = 3;
  return cli::WithRecipeDefaults(session, options);
}

TEST(StudioJobsTest, BothMethodsTrainSideBySideAndBothAreSaved) {
  const fs::path dir = RecordedSession("both");
  const store::Session session = store::Session::Open(dir.string());
  JobThread jobs;
  EXPECT_EQ(TrainMethods(jobs, session, QuickTraining(session), {"baseline", "recon"}), "Trained.");
  const std::vector<ui::TrainingView> views = jobs.Peek().training;
  ASSERT_EQ(views.size(), 2u);
  for (const ui::TrainingView& view : views) {
    EXPECT_TRUE(view.done) << view.method;
    EXPECT_FALSE(view.running) << view.method;
    EXPECT_EQ(view.step, 40) << view.method;
    EXPECT_TRUE(fs::exists(dir / "checkpoints" / (view.method + ".ckpt"))) << view.method;
  }
  EXPECT_FALSE(views[1].beacon_loss.empty());  // RECON's curve has its beacon term
  EXPECT_TRUE(views[0].beacon_loss.empty());
}

// A progress bar moves at every step, however long the run, while the loss curve keeps one
// point per window of steps (a million-step run would otherwise show step 0 for 5,000 steps).
TEST(StudioJobsTest, ProgressComesEveryStepAndTheCurveOncePerWindow) {
  const fs::path dir = RecordedSession("progress");
  const store::Session session = store::Session::Open(dir.string());
  cli::SessionTrainingOptions options = QuickTraining(session);
  options.steps = 400;  // a window of 2 steps for the curve's 200 points
  std::vector<int> steps;
  int curve_points = 0;
  const store::TrainingRecord record =
      cli::TrainSessionMethod(session, "baseline", options, [&](const cli::TrainingProgress& p) {
        if (p.step == 1) curve_points = 0;  // a restart (the authors' rule) begins a new curve
        steps.push_back(p.step);
        curve_points += p.curve_point ? 1 : 0;
      });
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(steps.back(), 400);
  for (size_t i = 1; i < steps.size(); ++i) {
    // Each step once, in order, or 1 where a restart begins again.
    EXPECT_TRUE(steps[i] == steps[i - 1] + 1 || steps[i] == 1)
        << "step " << steps[i] << " after " << steps[i - 1];
  }
  EXPECT_EQ(steps.size(), static_cast<size_t>(400 * record.attempts));
  EXPECT_EQ(curve_points, 200);
}

TEST(StudioJobsTest, AFailingMethodIsReportedAndTheOtherKeepsItsCheckpoint) {
  const fs::path dir = RecordedSession("one_fails");
  const store::Session session = store::Session::Open(dir.string());
  JobThread jobs;
  try {
    TrainMethods(jobs, session, QuickTraining(session), {"baseline", "nonsense"});
    ADD_FAILURE() << "an unknown method trained";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nonsense"));
  }
  const std::vector<ui::TrainingView> views = jobs.Peek().training;
  ASSERT_EQ(views.size(), 2u);
  EXPECT_TRUE(views[0].done);
  EXPECT_FALSE(views[1].done);
  EXPECT_FALSE(views[1].running);
  EXPECT_TRUE(fs::exists(dir / "checkpoints" / "baseline.ckpt"));
  EXPECT_FALSE(fs::exists(dir / "checkpoints" / "nonsense.ckpt"));
}

// Cancel is what the teacher asked for, not an error: the job ends normally and says what was
// kept. Here the cancel comes before either method finished, so nothing is saved.
TEST(StudioJobsTest, ACancelledTrainingSaysWhereEachMethodStoppedAndSavesNothing) {
  const fs::path dir = RecordedSession("cancel");
  const store::Session session = store::Session::Open(dir.string());
  JobThread jobs;
  cli::SessionTrainingOptions options = QuickTraining(session);
  options.steps = 100000;  // far longer than the cancel below waits
  std::string said;
  jobs.Start(JobKind::kTraining, [&](JobThread& j) -> std::function<void()> {
    said = TrainMethods(j, session, options, {"baseline", "recon"});
    return [] {};
  });
  // Cancel once both have reported progress (their data is loaded and steps are running).
  const auto both_running = [&] {
    const std::vector<ui::TrainingView> views = jobs.Peek().training;
    return views.size() == 2 && views[0].step > 0 && views[1].step > 0;
  };
  while (!both_running()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  jobs.Cancel();
  while (jobs.Peek().running) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const JobState ended = jobs.Take();
  EXPECT_EQ(ended.error, "") << "a cancel is not an error";
  EXPECT_NE(ended.finish, nullptr);
  EXPECT_THAT(said, HasSubstr("Training cancelled (Baseline at step "));
  EXPECT_THAT(said, HasSubstr("RECON (Play) at step "));
  EXPECT_THAT(said, HasSubstr("nothing of it was saved"));
  for (const ui::TrainingView& view : ended.training) {
    EXPECT_FALSE(view.running) << view.method;
    EXPECT_FALSE(view.done) << view.method;
  }
  EXPECT_FALSE(fs::exists(dir / "checkpoints" / "baseline.ckpt"));
  EXPECT_FALSE(fs::exists(dir / "checkpoints" / "recon.ckpt"));
}

// The rollouts report their progress over both methods, and a cancel writes nothing: the
// rollouts from before stay as they were.
TEST(StudioJobsTest, RolloutsShowProgressAndACancelWritesNothing) {
  const fs::path dir = RecordedSession("rollouts");
  const store::Session session = store::Session::Open(dir.string());
  {
    JobThread jobs;
    ASSERT_EQ(TrainMethods(jobs, session, QuickTraining(session), {"baseline", "recon"}),
              "Trained.");
  }
  const fs::path baseline_rollouts = dir / "rollouts" / "baseline.json";
  {
    JobThread jobs;
    jobs.Cancel();  // before the first step: deterministic, whatever the machine's speed
    EXPECT_THAT(RollOutTrainedMethods(jobs, session, 3), HasSubstr("Rollouts cancelled"));
    EXPECT_FALSE(fs::exists(baseline_rollouts));
    EXPECT_FALSE(fs::exists(dir / "rollouts" / "recon.json"));
  }
  JobThread jobs;
  EXPECT_EQ(RollOutTrainedMethods(jobs, session, 3), "Rollouts done.");
  const JobState state = jobs.Peek();
  EXPECT_GT(state.rollout_steps_total, 0);
  EXPECT_EQ(state.rollout_steps_done, state.rollout_steps_total) << "both methods, every step";
  EXPECT_TRUE(fs::exists(baseline_rollouts));
  EXPECT_TRUE(fs::exists(dir / "rollouts" / "recon.json"));
}

// Running() covers a job until its result is taken, a failure's included: the studio looks
// idle only once the screens can show how the job ended (a full disk made a failed training
// look idle while the screen still said "Training now").
TEST(StudioJobsTest, AJobCountsAsRunningUntilItsResultOrErrorIsTaken) {
  JobThread jobs;
  for (const bool fails : {false, true}) {
    SCOPED_TRACE(fails ? "a job that fails" : "a job that succeeds");
    std::atomic<bool> release{false};
    jobs.Start(JobKind::kTraining, [&](JobThread&) -> std::function<void()> {
      while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      if (fails) throw UserError("No space left on device");
      return [] {};
    });
    EXPECT_TRUE(jobs.Running());
    release = true;
    while (jobs.Peek().running) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_TRUE(jobs.Running()) << "over, but its result not taken yet";
    const JobState taken = jobs.Take();
    EXPECT_EQ(taken.error.empty(), !fails);
    EXPECT_EQ(taken.finish == nullptr, fails);
    EXPECT_FALSE(jobs.Running());
  }
}

}  // namespace
}  // namespace recon::studio
