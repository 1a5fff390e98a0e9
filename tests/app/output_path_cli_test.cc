// Every `--out` of recon: nothing lands inside a session folder except through the session, an
// existing file is replaced only with --force, and a folder of the user's is not written into.

#include "tests/app/session_cli_fixture.h"

namespace {

using namespace recon::session_cli_testing;  // NOLINT: the fixture and its helpers

TEST_F(SessionCliTest, AnOutputInsideASessionIsRefusedForEveryCommand) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 2").exit_code, 0);
  const std::map<std::string, std::string> before = SnapshotSession(session);
  const std::string episode = (session / "episodes" / "demo_0.h5").string();
  const std::string inside = (session / "play" / "new.png").string();
  for (const std::string& args : {
           "session export " + session.string() + " --out " + episode + " --force",
           "session export " + session.string() + " --out " + (session / "x.hdf5").string(),
           "render --scene tabletop --out " + inside + " --force",
           "calibrate --sim --points 4 --out " + (session / "session.json").string() + " --force",
           "experiment dynamic2d --runs 1 --tests 2 --demos 2 --steps 10 --out " +
               (session / "episodes").string() + " --force",
           "report " + session.string() + " --out " + (session / "episodes").string() + " --force",
       }) {
    const CommandResult r = RunRecon(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("is inside the teaching session")) << args;
    EXPECT_EQ(SnapshotSession(session), before) << args;
    EXPECT_FALSE(fs::exists(inside)) << args;
    EXPECT_FALSE(fs::exists(session / "x.hdf5")) << args;
  }
  // The session's own report folder is the report's to write, again and again.
  EXPECT_EQ(RunRecon("report " + session.string()).exit_code, 0);
  const CommandResult again =
      RunRecon("report " + session.string() + " --out " + (session / "report").string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

TEST_F(SessionCliTest, AnExistingFileIsReplacedOnlyWithForce) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 2").exit_code, 0);
  const fs::path mine = Path("mine.hdf5"), picture = Path("mine.png");
  std::ofstream(mine) << "the user's own file\n";
  std::ofstream(picture) << "the user's own picture\n";
  const std::string export_args = "session export " + session.string() + " --out " + mine.string();
  const std::string render_args = "render --scene tabletop --out " + picture.string();
  for (const std::string& args : {export_args, render_args}) {
    const CommandResult r = RunRecon(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("already exists; nothing was written (add --force"));
  }
  EXPECT_EQ(ReadBytes(mine), "the user's own file\n");
  EXPECT_EQ(ReadBytes(picture), "the user's own picture\n");
  EXPECT_EQ(RunRecon(export_args + " --force").exit_code, 0);
  EXPECT_EQ(RunRecon(render_args + " --force").exit_code, 0);
  EXPECT_NE(ReadBytes(mine), "the user's own file\n");
  EXPECT_NE(ReadBytes(picture), "the user's own picture\n");
  // A folder is not a file name.
  const CommandResult r = RunRecon(render_args.substr(0, render_args.find("--out")) + "--out " +
                                   root_.string() + " --force");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("is a folder"));
}

TEST_F(SessionCliTest, AFolderOfTheUsersIsNotWrittenInto) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 2").exit_code, 0);
  const fs::path papers = Path("papers");
  fs::create_directories(papers);
  std::ofstream(papers / "index.html") << "my page\n";
  for (const std::string& args : {
           "report " + session.string() + " --out " + papers.string(),
           "experiment dynamic2d --runs 1 --tests 2 --demos 2 --steps 10 --out " + papers.string(),
       }) {
    const CommandResult r = RunRecon(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("holds other files")) << args;
    EXPECT_EQ(std::distance(fs::directory_iterator(papers), fs::directory_iterator()), 1) << args;
  }
  EXPECT_EQ(ReadBytes(papers / "index.html"), "my page\n");
  const CommandResult forced =
      RunRecon("report " + session.string() + " --out " + papers.string() + " --force");
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_TRUE(fs::exists(papers / "report.html"));
  EXPECT_EQ(ReadBytes(papers / "index.html"), "my page\n");
}

}  // namespace
