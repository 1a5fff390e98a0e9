// A session folder that lost its session.json, and folders that are not sessions: `recon record`
// refuses them without touching a file, and `recon session repair` gives the lost manifest back
// after checking every episode against it.

#include "tests/app/session_cli_fixture.h"

namespace {

using namespace recon::session_cli_testing;  // NOLINT: the fixture and its helpers

/// The episode files' bytes (episodes/, play/, trash/), without the manifest.
std::map<std::string, std::string> EpisodeBytes(const fs::path& session) {
  std::map<std::string, std::string> files;
  for (const char* folder : {"episodes", "play", "trash"}) {
    if (!fs::is_directory(session / folder)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(session / folder)) {
      files[fs::relative(entry.path(), session).string()] = ReadBytes(entry.path());
    }
  }
  return files;
}

TEST_F(SessionCliTest, RecordIntoAFolderThatLostItsManifestIsRefusedAndRepairRestoresIt) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world dynamic2d --demos 3 --play 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  fs::remove(session / "session.json");
  const std::map<std::string, std::string> before = EpisodeBytes(session);
  ASSERT_EQ(before.size(), 5u);  // 3 demonstrations and the play data in 2 chunks

  // Recording a "new" session here would start again at demo_0 and replace the first take.
  r = Record(session, "--world dynamic2d --demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("5 episode file(s) but no session.json"));
  EXPECT_THAT(r.output, HasSubstr("recon session repair " + session.string()));
  EXPECT_EQ(EpisodeBytes(session), before);
  EXPECT_FALSE(fs::exists(session / "session.json"));
  // Reading commands name the missing manifest, too.
  r = RunRecon("session info " + session.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("session.json"));

  // A repair as another world disagrees with the episodes' shapes: refused, nothing written.
  r = RunRecon("session repair " + session.string() + " --world static2d");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("as a static2d session"));
  EXPECT_THAT(r.output, HasSubstr(".h5"));
  EXPECT_FALSE(fs::exists(session / "session.json"));
  EXPECT_EQ(EpisodeBytes(session), before);

  r = RunRecon("session repair " + session.string() + " --world dynamic2d");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("3 demonstration(s) and 2 play chunk(s)"));
  EXPECT_EQ(EpisodeBytes(session), before);
  const json info = Info(session);
  EXPECT_EQ(info["world"], "dynamic2d") << info.dump();
  EXPECT_EQ(info["episodes"], 3) << info.dump();
  EXPECT_EQ(info["damaged"].size(), 0u) << info.dump();
  EXPECT_EQ(ReadJson(session / "session.json")["cell"]["world"], "dynamic2d");

  // The repaired session appends after its last take, and the old takes stay as they were.
  r = Record(session, "--demos 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(DemoNames(Episodes(session)), ExpectedDemoNames(4));
  const std::map<std::string, std::string> after = EpisodeBytes(session);
  for (const auto& [file, bytes] : before) EXPECT_EQ(after.at(file), bytes) << file;
}

TEST_F(SessionCliTest, RepairKeepsAnUnreadableEpisodeListedAsDamaged) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 3").exit_code, 0);
  fs::remove(session / "session.json");
  const fs::path truncated = session / "episodes" / "demo_1.h5";
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  const CommandResult r = RunRecon("session repair " + session.string() + " --world dynamic2d");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("1 episode file(s) cannot be read"));
  const json info = Info(session);
  EXPECT_EQ(info["episodes"], 2) << info.dump();
  ASSERT_EQ(info["damaged"].size(), 1u) << info.dump();
  EXPECT_EQ(info["damaged"][0]["name"], "demo_1");
}

TEST_F(SessionCliTest, ANonEmptyFolderIsNotMadeASession) {
  const fs::path folder = Path("papers");
  fs::create_directories(folder);
  std::ofstream(folder / "notes.txt") << "my notes\n";
  const CommandResult r = Record(folder, "--world dynamic2d --demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("is not empty"));
  EXPECT_EQ(ReadBytes(folder / "notes.txt"), "my notes\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1);

  // An empty folder that already exists is fine.
  const fs::path empty = Path("empty");
  fs::create_directories(empty);
  const CommandResult made = Record(empty, "--world dynamic2d --demos 1");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_TRUE(fs::exists(empty / "session.json"));
}

TEST_F(SessionCliTest, RepairRefusesWhatIsNotADamagedSession) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 1").exit_code, 0);
  const std::string manifest = ReadBytes(session / "session.json");
  CommandResult r = RunRecon("session repair " + session.string() + " --world dynamic2d");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("nothing to repair"));
  EXPECT_EQ(ReadBytes(session / "session.json"), manifest);

  const fs::path empty = Path("empty");
  fs::create_directories(empty);
  r = RunRecon("session repair " + empty.string() + " --world dynamic2d");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("holds no episode files"));
  EXPECT_TRUE(fs::is_empty(empty));

  r = RunRecon("session repair " + session.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--world"));
  r = RunRecon("session repair " + Path("s2").string() + " --world nowhere");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("nowhere"));
}

}  // namespace
