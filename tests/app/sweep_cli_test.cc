// A sweep as a plan of units through the real binary: `--plan-only`, `run-unit` one unit at a
// time (in any order, one twice), and `collect` give the same results.csv, byte for byte, as the
// local run of the same experiment; a part-done sweep is collected with its missing units named;
// and every bad input is refused by name without touching a finished unit.

#include "tests/app/session_cli_fixture.h"

namespace recon::session_cli_testing {
namespace {

const std::string kSweep =
    "experiment dynamic2d --conditions baseline,exact,random --runs 2 --tests 10 --steps 150 "
    "--baseline-steps 100 --seed 3";

TEST_F(SessionCliTest, ASweepRunUnitByUnitEqualsTheLocalRunByteForByte) {
  const fs::path local = Path("local"), planned = Path("planned");
  CommandResult r = RunRecon(kSweep + " --jobs 2 --out " + local.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  r = RunRecon(kSweep + " --plan-only --out " + planned.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("planned 6 units"));
  EXPECT_FALSE(fs::exists(planned / "results.csv"));  // nothing trained
  const json plan = ReadJson(planned / "plan.json");
  EXPECT_EQ(plan["units"].size(), 6u);
  EXPECT_EQ(plan["arguments"][0], "dynamic2d");
  // The same plan as the local run made, but for where it went.
  EXPECT_EQ(ReadBytes(planned / "plan.json"), ReadBytes(local / "plan.json"));

  // Nothing done yet: collect writes nothing.
  r = RunRecon("experiment collect " + planned.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("no unit of"));
  EXPECT_FALSE(fs::exists(planned / "summary.json"));

  // Some units, out of order: collect names the missing ones.
  r = RunRecon("experiment run-unit " + planned.string() + " --unit 4 --unit 0-1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment collect " + planned.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("3 unit(s) missing: 2,3,5"));

  // The rest; unit 4 again is left as it was.
  const std::string unit4 = ReadBytes(planned / "units" / "unit_4.json");
  r = RunRecon("experiment run-unit " + planned.string() + " --unit 2,3,5 --unit 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("unit 4 is done already"));
  EXPECT_EQ(ReadBytes(planned / "units" / "unit_4.json"), unit4);
  r = RunRecon("experiment collect " + planned.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("every unit is done"));
  EXPECT_EQ(ReadBytes(planned / "results.csv"), ReadBytes(local / "results.csv"));
  for (int k = 0; k < 6; ++k) {
    const std::string unit = "units/unit_" + std::to_string(k) + ".json";
    EXPECT_EQ(ReadBytes(planned / unit), ReadBytes(local / unit)) << unit;
  }

  // A unit run again after its file was truncated (a crash of the disk, not of the writer).
  const std::string unit2 = ReadBytes(planned / "units" / "unit_2.json");
  std::ofstream(planned / "units" / "unit_2.json") << unit2.substr(0, 40);
  r = RunRecon("experiment collect " + planned.string());
  EXPECT_THAT(r.output, HasSubstr("unit_2.json is damaged"));
  EXPECT_THAT(r.output, HasSubstr("1 unit(s) missing: 2"));
  r = RunRecon("experiment run-unit " + planned.string() + " --unit 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadBytes(planned / "units" / "unit_2.json"), unit2);
}

TEST_F(SessionCliTest, ASweepRefusesBadInputByNameAndKeepsItsFinishedUnits) {
  const fs::path dir = Path("sweep");
  CommandResult r = RunRecon(kSweep + " --plan-only --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment run-unit " + dir.string() + " --unit 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string unit1 = ReadBytes(dir / "units" / "unit_1.json");
  const std::string plan = ReadBytes(dir / "plan.json");

  const struct {
    std::string args, words;
  } cases[] = {
      {"experiment run-unit " + dir.string() + " --unit 6", "the plan's units are 0 to 5"},
      {"experiment run-unit " + dir.string() + " --unit -1", "--unit"},
      {"experiment run-unit " + dir.string() + " --unit 3-1", "--unit 3-1"},
      {"experiment run-unit " + dir.string() + " --unit x", "expected a unit number"},
      {"experiment run-unit " + dir.string(), "--unit"},
      {"experiment run-unit " + Path("nowhere").string() + " --unit 0", "no plan in"},
      {"experiment collect " + Path("nowhere").string(), "no plan in"},
      // Another sweep into the same folder: refused unless --force.
      {"experiment dynamic2d --conditions baseline --runs 1 --tests 4 --plan-only --out " +
           dir.string(),
       "holds the plan of another sweep"},
  };
  for (const auto& c : cases) {
    r = RunRecon(c.args);
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_THAT(r.output, HasSubstr(c.words)) << c.args;
    EXPECT_EQ(ReadBytes(dir / "units" / "unit_1.json"), unit1) << c.args;
    EXPECT_EQ(ReadBytes(dir / "plan.json"), plan) << c.args;
  }
  // No Slurm here: no sbatch on PATH is a clear error, and nothing is submitted.
  r = RunCommand("env PATH=/nonexistent " + std::string(RECON_CLI) + " experiment submit " +
                 dir.string() + " --slurm 2>&1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("no sbatch on PATH"));
  EXPECT_FALSE(fs::exists(dir / "slurm"));
  // Two collects at once: both finish, and what they leave is whole.
  const std::string collect =
      std::string(RECON_CLI) + " experiment collect " + dir.string() + " > /dev/null 2>&1";
  r = RunCommand("(" + collect + " & " + collect + "; first=$?; wait $!; echo $first $?)");
  EXPECT_EQ(r.output, "0 0\n");
  const std::string csv = ReadBytes(dir / "results.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2);  // the header and unit 1's row
  EXPECT_TRUE(ReadJson(dir / "summary.json").contains("conditions"));

  // A plan edited by hand is refused before anything runs.
  json edited = ReadJson(dir / "plan.json");
  edited["arguments"][4] = "3";
  std::ofstream(dir / "plan.json") << edited.dump(2);
  r = RunRecon("experiment run-unit " + dir.string() + " --unit 0");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("changed since it was written"));
  EXPECT_FALSE(fs::exists(dir / "units" / "unit_0.json"));
}

// A plan nothing ran from holds no work: the corrected command replaces it without --force.
// Once a unit has a result, or the plan went to a cluster, it is refused as before.
TEST_F(SessionCliTest, APlanNothingRanFromIsReplacedByTheCorrectedCommand) {
  const fs::path dir = Path("corrected");
  CommandResult r = RunRecon(kSweep + " --plan-only --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string other =
      "experiment dynamic2d --conditions baseline --runs 1 --tests 4 --steps 50 "
      "--baseline-steps 50 --seed 5";
  r = RunRecon(other + " --plan-only --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadJson(dir / "plan.json")["units"].size(), 1u);

  // One unit of it ran: another command is refused and the plan and result are kept.
  r = RunRecon("experiment run-unit " + dir.string() + " --unit 0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string plan = ReadBytes(dir / "plan.json");
  r = RunRecon(kSweep + " --plan-only --out " + dir.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("holds the plan of another sweep"));
  EXPECT_EQ(ReadBytes(dir / "plan.json"), plan);
  EXPECT_TRUE(fs::exists(dir / "units" / "unit_0.json"));

  // A plan handed to a cluster (slurm/ exists) is refused even before any unit finished.
  const fs::path sent = Path("sent");
  r = RunRecon(kSweep + " --plan-only --out " + sent.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  fs::create_directories(sent / "slurm");
  r = RunRecon(other + " --plan-only --out " + sent.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("holds the plan of another sweep"));
  EXPECT_EQ(ReadJson(sent / "plan.json")["units"].size(), 6u);
}

// `text` quoted for the shell the test's commands run in (a line break stays inside the quotes).
std::string ShellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// `submit` writes a job script that a shell runs: a folder with a space arrives whole, and
// nothing a user gives (a folder with a line break, --time, --partition) can end one of its
// lines and add a command.
TEST_F(SessionCliTest, ASubmittedScriptCarriesAnyFolderAndNoAddedCommand) {
  const fs::path spaced = Path("my sweep");
  CommandResult r = RunRecon(kSweep + " --plan-only --out " + ShellQuoted(spaced.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string submit = "experiment submit " + ShellQuoted(spaced.string()) + " --slurm ";
  r = RunRecon(submit + "--dry-run --time 1-2:30 --partition gpu,cpu");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("#!/bin/bash\n", 0), 0u) << r.output;  // sbatch wants it first
  EXPECT_THAT(r.output, HasSubstr("run-unit '" + spaced.string() + "' --unit"));
  EXPECT_THAT(r.output,
              HasSubstr("'--output=" + spaced.string() + "/slurm/task_%A_%a.log' 'SCRIPT'"));
  EXPECT_THAT(r.output, HasSubstr("#SBATCH --time=1-2:30\n#SBATCH --partition=gpu,cpu\n"));

  const std::string injected = "\ntouch " + Path("added").string();
  for (const std::string& option : {"--time", "--partition"}) {
    r = RunRecon(submit + "--dry-run " + option + " " + ShellQuoted("1" + injected));
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(option + ": a ")) << r.output;
    EXPECT_THAT(r.output, Not(HasSubstr("#!/bin/bash")));
  }

  const fs::path broken = Path("sweep" + injected);
  r = RunRecon(kSweep + " --plan-only --out " + ShellQuoted(broken.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment submit " + ShellQuoted(broken.string()) + " --slurm --dry-run");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("its path holds a line break"));
  EXPECT_THAT(r.output, Not(HasSubstr("#!/bin/bash")));
  const fs::path percent = Path("sweep_%j");
  r = RunRecon(kSweep + " --plan-only --out " + percent.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("experiment submit " + percent.string() + " --slurm --dry-run");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Slurm reads as a file-name pattern"));
  EXPECT_FALSE(fs::exists(Path("added")));
}

}  // namespace
}  // namespace recon::session_cli_testing
