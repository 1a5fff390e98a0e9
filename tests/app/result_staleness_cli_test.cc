// A trained model and its rollouts say when the session changed under them: `session info`
// (text and JSON) and the report mark them out of date, naming what changed, until the method
// is retrained and rolled out again.

#include "tests/app/session_cli_fixture.h"

namespace recon::session_cli_testing {
namespace {

json OutOfDate(const json& info, const char* kind, const char* method) {
  return info[kind][method]["out_of_date"];
}

TEST_F(SessionCliTest, ResultsAreMarkedOutOfDateWhenTheSessionChangesUnderThem) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world dynamic2d --demos 4 --play 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --methods baseline,recon --steps 30");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("eval --session " + session.string() + " --tests 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json info = Info(session);
  for (const char* method : {"baseline", "recon"}) {
    EXPECT_TRUE(OutOfDate(info, "training", method).is_null()) << info.dump(1);
    EXPECT_TRUE(OutOfDate(info, "rollouts", method).is_null()) << info.dump(1);
  }

  // Two demonstrations more and one marked bad: both models learnt from another set.
  r = Record(session, "--demos 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("session mark " + session.string() + " demo_1 --bad");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  info = Info(session);
  ASSERT_TRUE(OutOfDate(info, "training", "baseline").is_string()) << info.dump(1);
  const std::string baseline = OutOfDate(info, "training", "baseline").get<std::string>();
  EXPECT_THAT(baseline, HasSubstr("trained on 4 demonstrations;"));
  EXPECT_THAT(baseline, HasSubstr("demo_4, demo_5 were added"));
  EXPECT_THAT(baseline, HasSubstr("demo_1 has left it"));
  ASSERT_TRUE(OutOfDate(info, "training", "recon").is_string());
  EXPECT_THAT(OutOfDate(info, "training", "recon").get<std::string>(),
              HasSubstr("trained on 4 demonstrations and"));
  ASSERT_TRUE(OutOfDate(info, "rollouts", "baseline").is_string());
  EXPECT_THAT(OutOfDate(info, "rollouts", "baseline").get<std::string>(),
              HasSubstr("retrain and roll out again"));
  r = RunRecon("session info " + session.string());
  EXPECT_THAT(r.output, HasSubstr("OUT OF DATE:    baseline: trained on 4 demonstrations"));
  r = RunRecon("report " + session.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = ReadBytes(session / "report" / "report.html");
  EXPECT_THAT(html, HasSubstr("<strong>Out of date:</strong> Baseline: trained on 4"));
  EXPECT_THAT(html, HasSubstr("<strong>Out of date:</strong> Baseline rollouts:"));

  // Retraining the Baseline brings its model up to date; its rollouts are now of an older model.
  r = RunRecon("train --session " + session.string() + " --methods baseline --steps 30");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  info = Info(session);
  EXPECT_TRUE(OutOfDate(info, "training", "baseline").is_null()) << info.dump(1);
  ASSERT_TRUE(OutOfDate(info, "rollouts", "baseline").is_string());
  EXPECT_THAT(OutOfDate(info, "rollouts", "baseline").get<std::string>(),
              HasSubstr("the model was retrained after these rollouts"));
  EXPECT_TRUE(OutOfDate(info, "training", "recon").is_string());

  // Rolled out again: nothing of the Baseline is out of date, RECON still is.
  r = RunRecon("eval --session " + session.string() + " --tests 2 --methods baseline");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  info = Info(session);
  EXPECT_TRUE(OutOfDate(info, "rollouts", "baseline").is_null()) << info.dump(1);
  EXPECT_TRUE(OutOfDate(info, "rollouts", "recon").is_string());
  r = RunRecon("report " + session.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(ReadBytes(session / "report" / "report.html"),
              Not(HasSubstr("<strong>Out of date:</strong> Baseline")));
}

}  // namespace
}  // namespace recon::session_cli_testing
