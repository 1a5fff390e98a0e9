// Bad input to the teaching-session commands, through the real `recon` binary: corrupt manifests
// and episodes, garbage files, an unwritable folder and wrong arguments give exit code 2 with a
// message naming the file and field, and change nothing already saved.

#include "tests/app/session_cli_fixture.h"

namespace {

using namespace recon::session_cli_testing;  // NOLINT: the fixture and its helpers

// 7a, 7b. A broken manifest is named with its field.
TEST_F(SessionCliTest, CorruptManifestIsNamedWithItsField) {
  const fs::path session = Path("s");
  const CommandResult r = Record(session, "--world dynamic2d --demos 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json manifest = ReadJson(session / "session.json");
  ASSERT_TRUE(manifest["cell"].contains("world")) << manifest.dump();

  json missing = manifest;
  missing["cell"].erase("world");
  WriteJson(session / "session.json", missing);
  CommandResult info = RunRecon("session info " + session.string() + " --json");
  EXPECT_EQ(info.exit_code, 2) << info.output;
  EXPECT_THAT(info.output, HasSubstr((session / "session.json").string()));
  EXPECT_THAT(info.output, HasSubstr("cell.world"));

  json newer = manifest;
  newer["version"] = 99;
  WriteJson(session / "session.json", newer);
  info = RunRecon("session info " + session.string());
  EXPECT_EQ(info.exit_code, 2) << info.output;
  EXPECT_THAT(info.output, HasSubstr("session.json"));
  EXPECT_THAT(info.output, HasSubstr("99"));
  EXPECT_THAT(info.output, HasSubstr("newer"));
}

// 7c. A truncated episode is listed as damaged, stops training, and can be deleted.
TEST_F(SessionCliTest, TruncatedEpisodeIsDamagedUntilDeleted) {
  const fs::path session = Path("s");
  constexpr int kDemos = 3;
  CommandResult r =
      Record(session, "--world dynamic2d --demos " + std::to_string(kDemos) + " --play 6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path episode = session / "episodes" / "demo_1.h5";
  ASSERT_TRUE(fs::exists(episode));
  fs::resize_file(episode, fs::file_size(episode) / 2);

  const json info = Info(session);
  EXPECT_EQ(info["episodes"], kDemos - 1);
  ASSERT_EQ(info["damaged"].size(), 1u) << info.dump();
  EXPECT_EQ(info["damaged"][0]["name"], "demo_1");
  EXPECT_THAT(info["damaged"][0].value("problem", ""), HasSubstr("demo_1.h5"));

  r = RunRecon("train --session " + session.string() + " --steps 200");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(episode.string()));
  EXPECT_FALSE(fs::exists(session / "checkpoints" / "baseline.ckpt"));

  r = RunRecon("session delete-episode " + session.string() + " demo_1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(session / "trash" / "demo_1.h5"));
  r = RunRecon("train --session " + session.string() + " --steps 200");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(session / "checkpoints" / "baseline.ckpt"));
  EXPECT_TRUE(fs::exists(session / "checkpoints" / "recon.ckpt"));
  EXPECT_EQ(ReadJson(session / "training" / "baseline.json")["train_demos"], kDemos - 1);
  // Without --lr the world's recipe decides (Dynamic 2D: the authors' 4e-4).
  EXPECT_DOUBLE_EQ(ReadJson(session / "training" / "baseline.json")["learning_rate"], 4e-4);
}

// 7d. A file that is not HDF5 is refused before any session is made.
TEST_F(SessionCliTest, ImportOfGarbageNamesTheFileAndCreatesNothing) {
  const fs::path garbage = Path("garbage.hdf5");
  std::ofstream(garbage) << "this is not an HDF5 file, just some text\n";
  const fs::path session = Path("imported");
  const CommandResult r =
      RunRecon("session import " + garbage.string() + " --session " + session.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(garbage.string()));
  EXPECT_FALSE(fs::exists(session));
  for (const fs::directory_entry& entry : fs::directory_iterator(root_)) {
    EXPECT_EQ(entry.path(), garbage) << "left behind: " << entry.path();
  }
}

// 8. A session folder the user cannot write is refused before anything is recorded.
TEST_F(SessionCliTest, UnwritableSessionFolderIsRefusedAndUnchanged) {
  const fs::path session = Path("s");
  constexpr int kDemos = 2;
  CommandResult r = Record(session, "--world dynamic2d --demos " + std::to_string(kDemos));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto files = SnapshotSession(session);

  std::string as_user;  // prefix running recon as a user who cannot write the session
  if (geteuid() == 0) {
    if (RunCommand("command -v setpriv").exit_code != 0) GTEST_SKIP() << "no setpriv";
    as_user = "setpriv --reuid=" + std::to_string(kNobody) + " --regid=" + std::to_string(kNobody) +
              " --clear-groups ";
    struct stat st {};
    ASSERT_EQ(stat(session.c_str(), &st), 0);
    ASSERT_EQ(st.st_uid, 0u);
    ASSERT_EQ(st.st_mode & 0777, 0755u);
  } else {
    fs::permissions(session, fs::perms(0555));
  }

  r = RunCommand(as_user + RECON_CLI + " record --session " + session.string() + " --demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("session folder " + session.string() + " is not writable"));
  // Reading still works.
  r = RunCommand(as_user + RECON_CLI + " session info " + session.string() + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ParseJsonOutput(r)["episodes"], kDemos);

  if (geteuid() != 0) fs::permissions(session, fs::perms(0755));
  EXPECT_EQ(SnapshotSession(session), files);
}

// 10. Wrong arguments are usage errors.
TEST_F(SessionCliTest, WrongArgumentsAreRefused) {
  const fs::path fresh = Path("fresh");
  CommandResult r = Record(fresh, "--world dynamic2d --demos -1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--demos"));
  EXPECT_FALSE(fs::exists(fresh / "session.json"));

  const fs::path session = Path("s");
  r = Record(session, "--world dynamic2d --demos 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  r = RunRecon("train --session " + session.string() + " --methods foo --steps 200");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("foo"));
  EXPECT_THAT(r.output, HasSubstr("recon"));
  EXPECT_THAT(r.output, HasSubstr("baseline"));
  EXPECT_FALSE(fs::exists(session / "checkpoints"));
  // A learning rate that is no rate: refused by name (0 is not "the recipe's" when typed).
  for (const char* lr : {"0", "-0.001", "nan"}) {
    r = RunRecon("train --session " + session.string() + " --steps 200 --lr " + lr);
    EXPECT_EQ(r.exit_code, 2) << lr << ": " << r.output;
    EXPECT_THAT(r.output, ::testing::AnyOf(HasSubstr("--lr"), HasSubstr("learning_rate"))) << lr;
    EXPECT_FALSE(fs::exists(session / "checkpoints")) << lr;
  }

  const std::string manifest = ReadBytes(session / "session.json");
  r = RunRecon("session mark " + session.string() + " demo_0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--bad"));
  r = RunRecon("session mark " + session.string() + " demo_0 --split sideways");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("sideways"));
  EXPECT_EQ(ReadBytes(session / "session.json"), manifest);
}

// A tabletop session keeps its layout and its noise settings; recording into it with others, or
// a demonstration count that would leave a configuration half-recorded, is refused by name and
// changes nothing.
TEST_F(SessionCliTest, TabletopProtocolMismatchesAreRefusedAndChangeNothing) {
  const fs::path session = Path("t");
  CommandResult r = Record(session, "--world tabletop --image-size 32 --demos 2 --no-calibration");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("demo_0..demo_1 are takes of configurations 0..0"));
  const json manifest = ReadJson(session / "session.json");
  EXPECT_EQ(manifest["cell"]["layout"], "paper");
  EXPECT_DOUBLE_EQ(manifest["cell"]["beacon_noise_sigma"].get<double>(), 0.07);
  EXPECT_DOUBLE_EQ(manifest["cell"]["demo_noise_sigma"].get<double>(), 0.0);
  const std::string before = ReadBytes(session / "session.json");
  const auto demo_bytes = ReadBytes(session / "episodes" / "demo_1.h5");

  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--layout wide --demos 2", "the session records layout 'paper' but 'wide' was asked for"},
      {"--demos 3",
       "--demos 3: the tabletop paper layout records 2 demonstrations per "
       "configuration"},
      {"--noise 0.02 --demos 2", "--noise is fixed when a session is created"},
      {"--demo-noise 0.05 --demos 2", "--demo-noise is fixed when a session is created"},
  };
  for (const auto& c : cases) {
    r = Record(session, c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(ReadBytes(session / "session.json"), before) << c.args;
    EXPECT_FALSE(fs::exists(session / "episodes" / "demo_2.h5")) << c.args;
  }
  EXPECT_EQ(ReadBytes(session / "episodes" / "demo_1.h5"), demo_bytes);

  // A new session: an unknown layout, or one on a world without layouts, is named.
  r = Record(Path("u"), "--world tabletop --layout diagonal --demos 2 --no-calibration");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--layout 'diagonal' does not exist; valid: paper, wide"));
  EXPECT_FALSE(fs::exists(Path("u") / "session.json"));
  r = Record(Path("v"), "--world dynamic2d --layout paper --demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("the dynamic2d world has no layouts"));
}

}  // namespace

namespace {

using namespace recon::session_cli_testing;  // NOLINT: the fixture and its helpers

std::map<std::string, std::string> FolderBytes(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    files[entry.path().filename().string()] = ReadBytes(entry.path());
  }
  return files;
}

void TruncateToHalf(const fs::path& file) { fs::resize_file(file, fs::file_size(file) / 2); }

// Train and eval read everything they need before they replace the first result.
TEST_F(SessionCliTest, ADamagedInputIsFoundBeforeAnyResultIsReplaced) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 3 --play 4").exit_code, 0);
  CommandResult r = RunRecon("train --session " + session.string() + " --steps 50");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("eval --session " + session.string() + " --tests 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto checkpoints = FolderBytes(session / "checkpoints");
  const auto training = FolderBytes(session / "training");
  const auto rollouts = FolderBytes(session / "rollouts");
  ASSERT_EQ(checkpoints.size(), 2u);

  // A damaged play chunk: only RECON reads play, and the Baseline trains first.
  const fs::path play = session / "play" / "play_1.h5";
  const std::string play_bytes = ReadBytes(play);
  TruncateToHalf(play);
  r = RunRecon("train --session " + session.string() + " --steps 60");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(play.string()));
  EXPECT_EQ(FolderBytes(session / "checkpoints"), checkpoints);
  EXPECT_EQ(FolderBytes(session / "training"), training);
  std::ofstream(play, std::ios::binary | std::ios::trunc) << play_bytes;

  // A damaged RECON checkpoint: the Baseline's rollouts come first.
  TruncateToHalf(session / "checkpoints" / "recon.ckpt");
  r = RunRecon("eval --session " + session.string() + " --tests 3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("recon.ckpt"));
  EXPECT_EQ(FolderBytes(session / "rollouts"), rollouts);
}

// What is not a file where a session's file should be: a named pipe (its reader would wait for a
// writer), a link to /dev/zero (a read that never ends), a link loop. Every reader ends, names
// the file and says what is there; a model that is gone is left out of eval with a word.
TEST_F(SessionCliTest, WhatIsNotAFileInASessionIsRefusedByName) {
  const fs::path session = Path("s");
  ASSERT_EQ(Record(session, "--world dynamic2d --demos 2 --play 2").exit_code, 0);
  CommandResult r = RunRecon("train --session " + session.string() + " --steps 20");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto replace = [](const fs::path& file, const std::string& by) {
    fs::remove(file);
    if (by == "fifo") {
      ASSERT_EQ(mkfifo(file.c_str(), 0644), 0) << file;
    } else {
      fs::create_symlink(by, file);
    }
  };
  const auto restore = [](const fs::path& file, const std::string& bytes) {
    fs::remove(file);
    std::ofstream(file, std::ios::binary) << bytes;
  };

  const fs::path manifest = session / "session.json";
  const std::string manifest_bytes = ReadBytes(manifest);
  replace(manifest, "fifo");
  r = RunRecon("session info " + session.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(manifest.string() + ": is a named pipe (FIFO), not a file"));
  replace(manifest, manifest.filename().string());  // a link to itself
  r = RunRecon("train --session " + session.string() + " --steps 20");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(manifest.string()));
  EXPECT_THAT(r.output, HasSubstr("Too many levels of symbolic links"));
  EXPECT_THAT(r.output, Not(HasSubstr("internal error")));
  restore(manifest, manifest_bytes);

  const fs::path demo = session / "episodes" / "demo_0.h5";
  const std::string demo_bytes = ReadBytes(demo);
  replace(demo, "/dev/zero");
  const json info = Info(session);
  ASSERT_EQ(info["damaged"].size(), 1u) << info.dump();
  EXPECT_THAT(info["damaged"][0].value("problem", ""),
              HasSubstr(demo.string() + ": is a device, not a file"));
  r = RunRecon("session export " + session.string() + " --out " + Path("x.hdf5").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(demo.string()));
  EXPECT_FALSE(fs::exists(Path("x.hdf5")));
  restore(demo, demo_bytes);

  const fs::path recon_model = session / "checkpoints" / "recon.ckpt";
  replace(recon_model, "fifo");
  r = RunRecon("eval --session " + session.string() + " --tests 2 --methods recon");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(recon_model.string() + ": is a named pipe (FIFO), not a file"));
  EXPECT_FALSE(fs::exists(session / "rollouts" / "recon.json"));
  fs::remove(recon_model);
  r = RunRecon("eval --session " + session.string() + " --tests 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("recon was trained (training/recon.json) but its model "
                                  "checkpoints/recon.ckpt is gone: it is left out"));
  EXPECT_TRUE(fs::exists(session / "rollouts" / "baseline.json"));
  EXPECT_FALSE(fs::exists(session / "rollouts" / "recon.json"));
}

}  // namespace
