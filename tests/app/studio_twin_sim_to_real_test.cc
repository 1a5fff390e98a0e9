// A session taught, trained and rolled out in the simulated cell, brought to a real cell's arm
// (the digital twin of tests/app/twin_rig.h) for trials of its policies: sim to real. The studio
// records nothing there (its beacons, calibration and data belong to the simulated cell), runs
// the trials on the same test scenes as the simulated rollouts, and the session keeps both,
// labelled apart, in the studio, `recon session info` and the report.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "app/cli/result_staleness.h"
#include "app/cli/session_summary.h"
#include "app/studio/studio_controller.h"
#include "engine/store/real_trials.h"
#include "engine/store/rollout_summary.h"
#include "engine/store/session.h"
#include "tests/app/run_recon.h"
#include "tests/app/studio_twin_fixture.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using testing::StudioTwinCellTest;
using testing::WaitFor;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(StudioTwinCellTest, ASimulatedSessionRunsTrialsOnTheRealArmAndKeepsBothResultsLabelled) {
  // Taught, trained and rolled out in the simulated cell, from the command line.
  const fs::path session_dir = dir_ / "session";
  for (const std::string& args :
       {"record --session " + session_dir.string() + " --world tabletop --demos 2 --seed 70",
        "train --session " + session_dir.string() + " --method baseline --steps 20 --seed 3",
        "eval --session " + session_dir.string() + " --tests 3 --seed 11"}) {
    const recon::testing::CommandResult run = recon::testing::RunRecon(args);
    ASSERT_EQ(run.exit_code, 0) << args << "\n" << run.output;
  }
  const std::string manifest_before = ReadText(session_dir / "session.json");

  // Opened on the real cell: the cell's own steps are blocked, saying why and where to go.
  StudioController controller(Options());
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) {
    return now.session_open && now.camera_frame > 0 && !now.rollouts.empty();
  });
  EXPECT_EQ(s.cell_kind, "simulated");
  EXPECT_EQ(s.studio_cell, "real");
  for (teach::Step step :
       {teach::Step::kBeacons, teach::Step::kCalibrate, teach::Step::kRecord, teach::Step::kPlay}) {
    const teach::StepStatus& status = s.steps[static_cast<size_t>(step)];
    EXPECT_EQ(status.state, teach::StepState::kBlocked) << teach::StepTitle(step);
    EXPECT_THAT(status.why_blocked, HasSubstr("Taught in the simulated cell"));
    EXPECT_THAT(status.why_blocked, HasSubstr("(Rollouts)"));
  }
  EXPECT_NE(s.steps[static_cast<size_t>(teach::Step::kTrain)].state, teach::StepState::kBlocked);
  EXPECT_NE(s.steps[static_cast<size_t>(teach::Step::kRollouts)].state, teach::StepState::kBlocked);

  // Every command that would record or calibrate is refused by name, and nothing is written.
  const ui::StudioCommand refused[] = {ui::AssignBeacon{"plate", "plate"}, ui::StartCalibration{},
                                       ui::StartRecording{}, ui::ReRecordEpisode{"demo_0"},
                                       ui::RecordPlay{10}};
  for (const ui::StudioCommand& command : refused) {
    controller.Push(command);
    s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
    EXPECT_THAT(s.errors.back(), HasSubstr("taught in the simulated cell"));
    EXPECT_THAT(s.errors.back(), HasSubstr("here"));
    EXPECT_FALSE(s.recording);
    EXPECT_FALSE(s.calibration.running);
    controller.Push(ui::DismissErrors{});
    s = WaitFor(controller, [](const auto& now) { return now.errors.empty(); });
  }
  EXPECT_EQ(ReadText(session_dir / "session.json"), manifest_before);

  // A trial of the simulated session's policy on the real arm sets up the first scene of the
  // simulated rollouts' test plan, so the two compare scene by scene.
  controller.Push(ui::StartTrials{"baseline", 1});
  s = WaitFor(controller,
              [](const auto& now) { return now.trial.phase == ui::TrialPhase::kSetUp; });
  const store::Session before =
      store::Session::Open(session_dir.string(), store::Session::Access::kReadOnly);
  const std::optional<store::RolloutSummary> simulated =
      store::ReadRolloutSummary(before, "baseline");
  ASSERT_TRUE(simulated.has_value());
  ASSERT_EQ(simulated->per_scenario.size(), 3u);
  EXPECT_EQ(s.trial.scene_seed, simulated->per_scenario[0].seed);
  rig_->SetUpLayout(s.trial);
  const int64_t commands = rig_->robot->commands_received();
  controller.Push(ui::RunTrial{});
  s = WaitFor(controller, [](const auto& now) {
    return now.trial.phase == ui::TrialPhase::kRunning && now.trial.step >= 3;
  });
  controller.Push(ui::StopTrial{});
  s = WaitFor(controller,
              [](const auto& now) { return now.trial.phase == ui::TrialPhase::kJudge; });
  EXPECT_GT(rig_->robot->commands_received(), commands + 3);  // the policy drove the real arm
  controller.Push(ui::JudgeTrial{false, "missed the toast"});
  s = WaitFor(controller, [](const auto& now) { return now.real_trials.size() == 1; });
  // The Rollouts step shows both: the simulated rollouts and the trials on the real arm.
  ASSERT_EQ(s.rollouts.size(), 1u);
  EXPECT_EQ(s.rollouts[0].tests, 3);
  EXPECT_EQ(s.real_trials[0].trials.size(), 1u);

  // Both in the session, labelled apart: the trials name the real cell they ran on.
  const store::Session session =
      store::Session::Open(session_dir.string(), store::Session::Access::kReadOnly);
  EXPECT_EQ(session.manifest().cell, "simulated");
  EXPECT_EQ(session.demos().size(), 2u);
  const std::optional<store::RealTrialLog> log = store::ReadRealTrialLog(session, "baseline");
  ASSERT_TRUE(log.has_value());
  ASSERT_EQ(log->trials.size(), 1u);
  EXPECT_THAT(log->cell, StartsWith("real (camera: "));
  const cli::SessionResults results = cli::ReadSessionResults(session);
  const std::string info =
      cli::SessionInfoText(session, cli::SessionInfoJson(session, results), results);
  EXPECT_THAT(info, HasSubstr("over 3 simulated scenarios"));
  EXPECT_THAT(info, HasSubstr("baseline: 0 of 1 succeeded on the real arm (real (camera: "));

  // The report: the simulated rollouts and the real trials, each trial beside the same scene's
  // simulated outcome.
  controller.Push(ui::WriteReport{});
  s = WaitFor(controller, [](const auto& now) { return !now.report_path.empty(); });
  const std::string html = ReadText(s.report_path);
  EXPECT_THAT(html, HasSubstr("Simulated rollouts: Baseline vs RECON"));
  EXPECT_THAT(html, HasSubstr("Trials on the real arm"));
  EXPECT_THAT(html, HasSubstr("Same scene, simulated"));
  // The trial's row ends with the simulated rollout's verdict on the same scene; the method's
  // row counts it.
  const bool simulated_success = simulated->per_scenario[0].succeeded;
  EXPECT_THAT(html, HasSubstr("<td>missed the toast</td><td>stopped by the person</td>"));
  EXPECT_THAT(html, HasSubstr(std::string("<td>") + (simulated_success ? "success" : "failure") +
                              "</td></tr>"));
  EXPECT_THAT(html, HasSubstr(std::string("<td class=\"num\">") + (simulated_success ? "1" : "0") +
                              " of 1</td></tr>"));
}

}  // namespace
}  // namespace recon::studio
