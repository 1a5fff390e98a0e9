// A sweep on a real Slurm (22.05: slurmctld, slurmd and munge as a one-node cluster on this
// machine, started by scripts/slurm-local for this suite and stopped by its PIDs afterwards):
// the units run as a job array give the local run's results.csv byte for byte; a unit cancelled
// while it runs (scancel, as a preemption would) leaves no result, is shown failed with the
// cluster's words, and is the only one a second submission runs; a partition or time limit
// the cluster does not take is refused with the cluster's words.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <regex>
#include <string>
#include <thread>

#include "tests/app/run_recon.h"

namespace recon {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using ::testing::HasSubstr;
using testing::RunCommand;
using testing::RunRecon;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class SlurmSweepTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("recon-slurm-" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    const CommandResult up = RunCommand(std::string(RECON_SOURCE_DIR) + "/scripts/slurm-local up " +
                                        (root_ / "cluster").string() + " 2>&1");
    up_ = up.exit_code == 0;
    up_output_ = up.output;
    setenv("SLURM_CONF", (root_ / "cluster" / "slurm.conf").c_str(), 1);
  }
  static void TearDownTestSuite() {
    RunCommand(std::string(RECON_SOURCE_DIR) + "/scripts/slurm-local down " +
               (root_ / "cluster").string());
    fs::remove_all(root_);
  }
  void SetUp() override {
    ASSERT_TRUE(up_) << "the one-node cluster did not start:\n" << up_output_;
  }

  /// The sweep's status once `done` holds for it; a failure after `timeout_s`.
  static std::string WaitForStatus(const fs::path& dir,
                                   const std::function<bool(const std::string&)>& done,
                                   double timeout_s = 180) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      const CommandResult r = RunRecon("experiment status " + dir.string());
      if (r.exit_code == 0 && done(r.output)) return r.output;
      if (std::chrono::steady_clock::now() > deadline) {
        ADD_FAILURE() << "timed out; the last status:\n" << r.output;
        return r.output;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
  }

  static fs::path root_;
  static bool up_;
  static std::string up_output_;
};

fs::path SlurmSweepTest::root_;
bool SlurmSweepTest::up_ = false;
std::string SlurmSweepTest::up_output_;

const std::string kSweep =
    "experiment dynamic2d --conditions baseline,exact,random --runs 2 --tests 10 --steps 150 "
    "--baseline-steps 100 --seed 3";

TEST_F(SlurmSweepTest, AJobArrayGivesTheLocalRunsResultsByteForByte) {
  const fs::path local = root_ / "local", array = root_ / "array";
  CommandResult r = RunRecon(kSweep + " --out " + local.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon(kSweep + " --plan-only --out " + array.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment submit " + array.string() + " --slurm --max-parallel 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("submitted job"));
  EXPECT_THAT(r.output, HasSubstr("6 unit(s) (0-5)"));
  WaitForStatus(array, [](const std::string& s) { return s.find("6 done") != std::string::npos; });
  r = RunRecon("experiment collect " + array.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadBytes(array / "results.csv"), ReadBytes(local / "results.csv"));
  // Each task logged where the scheduler put it.
  EXPECT_TRUE(fs::exists(array / "slurm" / "jobs.json"));
  // Everything done: a second submission has nothing to run.
  r = RunRecon("experiment submit " + array.string() + " --slurm");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("nothing to submit: 6 of 6 units done"));
  // A partition the cluster does not have: the cluster's refusal, nothing submitted.
  r = RunRecon("experiment dynamic2d --conditions baseline --runs 1 --tests 4 --plan-only --out " +
               (root_ / "refused").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment submit " + (root_ / "refused").string() + " --slurm --partition nosuch");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("invalid partition"));
  EXPECT_THAT(r.output, HasSubstr("nothing was submitted"));
  // A time limit in none of sbatch's forms: refused before the cluster is asked, with the
  // forms it takes, and no submission is recorded.
  r = RunRecon("experiment submit " + (root_ / "refused").string() + " --slurm --time soon");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--time: a time limit as sbatch takes it"));
  EXPECT_FALSE(fs::exists(root_ / "refused" / "slurm" / "jobs.json"));
  r = RunRecon("experiment status " + (root_ / "refused").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("1 units: 0 done, 0 running, 0 pending, 0 failed, 1 missing"));
  EXPECT_THAT(r.output, HasSubstr("never submitted"));
}

TEST_F(SlurmSweepTest, AUnitCancelledWhileItRunsIsTheOneASecondSubmissionRuns) {
  // Units of a few seconds each, so one can be caught running.
  const std::string sweep =
      "experiment dynamic2d --conditions baseline,exact --runs 2 --tests 10 --steps 3000 "
      "--baseline-steps 3000 --seed 5";
  const fs::path dir = root_ / "cancelled";
  CommandResult r = RunRecon(sweep + " --plan-only --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment submit " + dir.string() + " --slurm --max-parallel 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::smatch job = [&] {
    std::smatch m;
    std::regex_search(r.output, m, std::regex("submitted job (\\d+)"));
    return m;
  }();
  ASSERT_FALSE(job.empty()) << r.output;
  // Catch a unit running and hold its process (SIGSTOP), so that it cannot finish before the
  // cancel reaches it: the cancel then always lands half-way. A unit that ended between the
  // queue's word and the hold is let be, and the next one caught.
  std::string unit;
  for (int tries = 0; tries < 4 && unit.empty(); ++tries) {
    const std::string status = WaitForStatus(
        dir, [](const std::string& s) { return s.find("running: ") != std::string::npos; });
    std::smatch running;
    ASSERT_TRUE(std::regex_search(status, running, std::regex("running: (\\d+)"))) << status;
    const CommandResult held = RunCommand("pkill -STOP -f 'run-unit " + dir.string() + " --unit " +
                                          running[1].str() + "$'");
    if (held.exit_code == 0) unit = running[1];
  }
  ASSERT_FALSE(unit.empty()) << "no unit was caught running";
  r = RunCommand("scancel " + job[1].str() + "_" + unit + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Only the cancelled task leaves the queue; the others run on. Cancelled half-way: no
  // result, and the status says it failed and why, in the cluster's words from its log.
  const std::string status = WaitForStatus(dir, [&](const std::string& s) {
    return s.find("failed (submitted, ended without a result): " + unit + "\n") !=
           std::string::npos;
  });
  EXPECT_FALSE(fs::exists(dir / "units" / ("unit_" + unit + ".json")));
  EXPECT_THAT(status, HasSubstr("unit " + unit + ", job " + job[1].str() + "_" + unit + ": "));
  EXPECT_THAT(status, HasSubstr("CANCELLED"));
  EXPECT_THAT(status, HasSubstr("runs the failed"));
  WaitForStatus(dir, [](const std::string& s) {
    return s.find(" 0 running, 0 pending") != std::string::npos;
  });
  r = RunRecon("experiment submit " + dir.string() + " --slurm");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("1 unit(s) (" + unit + ")"));
  WaitForStatus(dir, [](const std::string& s) { return s.find("4 done") != std::string::npos; });
  r = RunRecon("experiment collect " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("every unit is done"));
  // The same as the sweep run here, unit for unit.
  const fs::path local = root_ / "cancelled_local";
  r = RunRecon(sweep + " --out " + local.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadBytes(dir / "results.csv"), ReadBytes(local / "results.csv"));
}

}  // namespace
}  // namespace recon
