// The teaching-session commands (record, session ..., train, eval, report), run end to end
// through the real `recon` binary as a teacher would: exit codes, JSON output and the files left
// in the session folder.

#include <map>
#include <string>

#include "tests/app/session_cli_fixture.h"

namespace {

using namespace recon::session_cli_testing;  // NOLINT: the fixture and its helpers

// 1. Recording creates the session; a second `record` appends to it.
TEST_F(SessionCliTest, RecordThenAppendCountsEverything) {
  const fs::path session = Path("s");
  constexpr int kDemos = 3, kPlay = 10, kMoreDemos = 2, kMorePlay = 7;
  CommandResult r = Record(session, "--world dynamic2d --demos " + std::to_string(kDemos) +
                                        " --play " + std::to_string(kPlay) + " --seed 5");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const auto check = [&](int demos, int play) {
    const json info = Info(session);
    const json episodes = Episodes(session);
    EXPECT_EQ(info["episodes"], demos);
    EXPECT_EQ(info["play"], play);
    EXPECT_EQ(info["world"], "dynamic2d");
    EXPECT_TRUE(info["damaged"].empty());
    EXPECT_EQ(DemoNames(episodes), ExpectedDemoNames(demos));
    int64_t demo_samples = 0, play_samples = 0;
    double teaching_seconds = 0;
    std::set<uint64_t> seeds;
    for (const json& e : episodes) {
      if (e["kind"] == "demo") {
        demo_samples += e["samples"].get<int64_t>();
        teaching_seconds += e["teaching_seconds"].get<double>();
        seeds.insert(e["seed"].get<uint64_t>());
        EXPECT_GT(e["samples"].get<int64_t>(), 0) << e.dump();
      } else {
        play_samples += e["samples"].get<int64_t>();
      }
    }
    EXPECT_EQ(info["demo_samples"], demo_samples);
    EXPECT_EQ(play_samples, play);
    // Every demonstration is its own scenario, appended ones included.
    EXPECT_EQ(seeds.size(), static_cast<size_t>(demos));
    EXPECT_EQ(info["teaching_time"]["demonstrations"], demos);
    EXPECT_NEAR(info["teaching_time"]["demonstrations_s"].get<double>(), teaching_seconds, 1e-6);
    EXPECT_TRUE(info["calibration"].is_null());
    EXPECT_TRUE(info["training"].empty());
    EXPECT_TRUE(info["rollouts"].empty());
  };
  check(kDemos, kPlay);

  r = Record(session,
             "--demos " + std::to_string(kMoreDemos) + " --play " + std::to_string(kMorePlay));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  check(kDemos + kMoreDemos, kPlay + kMorePlay);
}

// 2. A session keeps one world and one placement.
TEST_F(SessionCliTest, AppendingWithAnotherWorldOrPlacementChangesNothing) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world dynamic2d --demos 2 --play 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json before = Info(session);
  const std::string placement = before["placement"].get<std::string>();
  ASSERT_NE(placement, "other");
  const auto files = SnapshotSession(session);

  r = Record(session, "--world static2d --demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("'dynamic2d'"));
  EXPECT_THAT(r.output, HasSubstr("'static2d'"));

  r = Record(session, "--placement other --demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("'" + placement + "'"));
  EXPECT_THAT(r.output, HasSubstr("'other'"));

  const json after = Info(session);
  EXPECT_EQ(after["episodes"], before["episodes"]);
  EXPECT_EQ(after["play"], before["play"]);
  EXPECT_EQ(after["world"], "dynamic2d");
  EXPECT_EQ(after["placement"], placement);
  EXPECT_EQ(SnapshotSession(session), files);
}

// 3. A new session needs its world.
TEST_F(SessionCliTest, FirstRecordWithoutWorldAsksForIt) {
  const fs::path session = Path("s");
  const CommandResult r = Record(session, "--demos 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--world"));
  EXPECT_THAT(r.output, HasSubstr(session.string()));
  EXPECT_FALSE(fs::exists(session / "session.json"));
}

// 4. Deleting moves the file to trash/ and never frees its name.
TEST_F(SessionCliTest, DeleteEpisodeMovesToTrashAndNamesAreNotReused) {
  const fs::path session = Path("s");
  constexpr int kDemos = 3;
  CommandResult r = Record(session, "--world dynamic2d --demos " + std::to_string(kDemos));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string last = "demo_" + std::to_string(kDemos - 1);

  r = RunRecon("session delete-episode " + session.string() + " " + last);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(session / "episodes" / (last + ".h5")));
  EXPECT_TRUE(fs::exists(session / "trash" / (last + ".h5")));
  EXPECT_EQ(Info(session)["episodes"], kDemos - 1);

  // All named episodes must exist, or nothing is deleted; the error lists the known ones.
  r = RunRecon("session delete-episode " + session.string() + " demo_0 demo_99");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("demo_99"));
  for (int i = 0; i < kDemos - 1; ++i) {
    EXPECT_THAT(r.output, HasSubstr("demo_" + std::to_string(i)));
  }
  EXPECT_TRUE(fs::exists(session / "episodes" / "demo_0.h5"));

  r = Record(session, "--demos 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> expected = ExpectedDemoNames(kDemos - 1);
  expected.push_back("demo_" + std::to_string(kDemos));
  EXPECT_EQ(DemoNames(Episodes(session)), expected);
  EXPECT_TRUE(fs::exists(session / "trash" / (last + ".h5")));
}

// 5. Marks show in `episodes` and in the counts of `info`.
TEST_F(SessionCliTest, MarkBadSplitAndNote) {
  const fs::path session = Path("s");
  constexpr int kDemos = 4;
  CommandResult r = Record(session, "--world dynamic2d --demos " + std::to_string(kDemos));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string note = "wobbly grasp near the end";

  r = RunRecon("session mark " + session.string() + " demo_1 --bad");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("session mark " + session.string() + " demo_2 --split valid --note '" + note + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const json episodes = Episodes(session);
  const json* bad = FindEpisode(episodes, "demo_1");
  const json* valid = FindEpisode(episodes, "demo_2");
  const json* plain = FindEpisode(episodes, "demo_0");
  ASSERT_TRUE(bad != nullptr && valid != nullptr && plain != nullptr) << episodes.dump();
  EXPECT_EQ((*bad)["bad"], true);
  EXPECT_EQ((*valid)["bad"], false);
  EXPECT_EQ((*valid)["split"], "valid");
  EXPECT_EQ((*valid)["note"], note);
  EXPECT_EQ((*plain)["bad"], false);
  EXPECT_EQ((*plain)["split"], "train");
  EXPECT_EQ((*plain)["note"], "");

  json info = Info(session);
  EXPECT_EQ(info["episodes"], kDemos);
  EXPECT_EQ(info["bad"], 1);
  EXPECT_EQ(info["valid"], 1);
  EXPECT_EQ(info["train"], kDemos - 2);  // neither the bad one nor the validation one
  EXPECT_EQ(info["teaching_time"]["demonstrations"], kDemos - 1);

  r = RunRecon("session mark " + session.string() + " demo_1 --good");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  info = Info(session);
  EXPECT_EQ(info["bad"], 0);
  EXPECT_EQ(info["train"], kDemos - 1);
  EXPECT_EQ(info["valid"], 1);
}

// 5. The same seed draws the same validation split.
TEST_F(SessionCliTest, SplitIsReproducibleWithItsSeed) {
  constexpr int kDemos = 6;
  constexpr double kValid = 0.3;
  std::vector<std::map<std::string, std::string>> assignments;
  for (const char* name : {"a", "b"}) {
    const fs::path session = Path(name);
    CommandResult r =
        Record(session, "--world dynamic2d --seed 4 --demos " + std::to_string(kDemos));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = RunRecon("session split " + session.string() + " --valid 0.3 --seed 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::map<std::string, std::string> split;
    for (const json& e : Episodes(session)) {
      if (e["kind"] == "demo") split[e["name"].get<std::string>()] = e["split"];
    }
    assignments.push_back(split);
  }
  ASSERT_EQ(assignments[0].size(), static_cast<size_t>(kDemos));
  EXPECT_EQ(assignments[0], assignments[1]);
  const int expected_valid = static_cast<int>(kValid * kDemos + 0.5);
  int valid = 0;
  for (const auto& [name, split] : assignments[0]) valid += split == "valid";
  EXPECT_EQ(valid, expected_valid);
  const json info = Info(Path("a"));
  EXPECT_EQ(info["valid"], expected_valid);
  EXPECT_EQ(info["train"], kDemos - expected_valid);
}

// 6. Export to robomimic's layout, and import it back.
TEST_F(SessionCliTest, ExportWritesRobomimicLayoutAndImportRestoresTheSession) {
  const fs::path session = Path("s");
  constexpr int kDemos = 4, kPlay = 6;
  CommandResult r = Record(session, "--world dynamic2d --seed 2 --demos " + std::to_string(kDemos) +
                                        " --play " + std::to_string(kPlay));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("session mark " + session.string() + " demo_1 --bad");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("session mark " + session.string() + " demo_2 --split valid");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json original = Info(session);

  const fs::path plain = Path("plain.hdf5");
  r = RunRecon("session export " + session.string() + " --out " + plain.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(plain));
  CommandResult ls = RunCommand(std::string(H5LS) + " -r " + plain.string());
  ASSERT_EQ(ls.exit_code, 0) << ls.output;
  for (const char* demo : {"demo_0", "demo_2", "demo_3"}) {
    const std::string group = std::string("/data/") + demo + "/";
    for (const char* item : {"obs/", "next_obs/", "actions ", "rewards ", "dones ", "states "}) {
      EXPECT_THAT(ls.output, HasSubstr(group + item)) << ls.output;
    }
  }
  EXPECT_THAT(ls.output, Not(HasSubstr("/data/demo_1/"))) << "a bad demo was exported";
  EXPECT_THAT(ls.output, HasSubstr("/mask/train "));
  EXPECT_THAT(ls.output, HasSubstr("/mask/valid "));
  EXPECT_THAT(ls.output, HasSubstr("/play/"));
  const CommandResult masks =
      RunCommand(std::string(H5DUMP) + " -d /mask/valid -d /mask/train " + plain.string());
  ASSERT_EQ(masks.exit_code, 0) << masks.output;
  const size_t train_at = masks.output.find("/mask/train");
  ASSERT_NE(train_at, std::string::npos) << masks.output;
  const std::string valid_part = masks.output.substr(0, train_at);
  const std::string train_part = masks.output.substr(train_at);
  EXPECT_THAT(valid_part, HasSubstr("\"demo_2\""));
  EXPECT_THAT(train_part, HasSubstr("\"demo_0\""));
  EXPECT_THAT(train_part, HasSubstr("\"demo_3\""));
  EXPECT_THAT(train_part, Not(HasSubstr("\"demo_1\"")));

  const fs::path with_bad = Path("with_bad.hdf5");
  r = RunRecon("session export " + session.string() + " --include-bad --out " + with_bad.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ls = RunCommand(std::string(H5LS) + " -r " + with_bad.string());
  EXPECT_THAT(ls.output, HasSubstr("/data/demo_1/obs/"));

  const fs::path slim = Path("slim.hdf5");
  r = RunRecon("session export " + session.string() + " --no-play --no-next-obs --out " +
               slim.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ls = RunCommand(std::string(H5LS) + " -r " + slim.string());
  EXPECT_THAT(ls.output, HasSubstr("/data/demo_0/obs/"));
  EXPECT_THAT(ls.output, Not(HasSubstr("next_obs")));
  EXPECT_THAT(ls.output, Not(HasSubstr("/play")));

  const fs::path imported = Path("imported");
  r = RunRecon("session import " + with_bad.string() + " --session " + imported.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json copy = Info(imported);
  for (const char* key :
       {"episodes", "play", "demo_samples", "valid", "spec", "world", "placement", "beacons"}) {
    EXPECT_EQ(copy[key], original[key]) << key;
  }
  EXPECT_EQ(copy["episodes"], kDemos);
  EXPECT_EQ(copy["play"], kPlay);
}

// 9. Train, evaluate and report on a small session.
TEST_F(SessionCliTest, TrainEvalAndReport) {
  const fs::path session = Path("s");
  constexpr int kDemos = 6, kPlay = 30, kTests = 3;
  CommandResult r = Record(session, "--world dynamic2d --seed 3 --demos " + std::to_string(kDemos) +
                                        " --play " + std::to_string(kPlay));
  ASSERT_EQ(r.exit_code, 0) << r.output;

  r = RunRecon("eval --session " + session.string() + " --tests " + std::to_string(kTests));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("recon train --session " + session.string()));
  EXPECT_FALSE(fs::exists(session / "rollouts"));

  r = RunRecon("train --session " + session.string() + " --methods baseline,recon --steps 200");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("eval --session " + session.string() + " --tests " + std::to_string(kTests));
  ASSERT_EQ(r.exit_code, 0) << r.output;

  for (const char* method : {"baseline", "recon"}) {
    SCOPED_TRACE(method);
    const std::string file = std::string(method) + ".json";
    EXPECT_TRUE(fs::exists(session / "checkpoints" / (std::string(method) + ".ckpt")));
    ASSERT_TRUE(fs::exists(session / "training" / file));
    ASSERT_TRUE(fs::exists(session / "rollouts" / file));
    const json training = ReadJson(session / "training" / file);
    EXPECT_EQ(training["method"], method);
    EXPECT_EQ(training["train_demos"], kDemos);
    EXPECT_EQ(training["play_samples"], std::string(method) == "recon" ? kPlay : 0);
    const json rollout = ReadJson(session / "rollouts" / file);
    EXPECT_EQ(rollout["method"], method);
    EXPECT_EQ(rollout["tests"], kTests);
    EXPECT_EQ(rollout["per_scenario"].size(), static_cast<size_t>(kTests));
    ASSERT_TRUE(rollout["metric_mean"].is_number()) << rollout.dump();
    EXPECT_TRUE(std::isfinite(rollout["metric_mean"].get<double>()));
    // Dynamic 2D has no replay (session_replay_cli_test.cc covers a world that has one).
    EXPECT_FALSE(rollout.contains("replay")) << rollout.dump();
    EXPECT_FALSE(fs::exists(session / "rollouts" / (std::string(method) + ".replay.h5")));
  }
  const json info = Info(session);
  for (const char* method : {"baseline", "recon"}) {
    EXPECT_TRUE(info["training"].contains(method)) << info["training"].dump();
    EXPECT_TRUE(info["rollouts"].contains(method));
    EXPECT_EQ(info["rollouts"][method]["tests"], kTests);
  }

  r = RunRecon("report " + session.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path html_path = session / "report" / "report.html";
  ASSERT_TRUE(fs::exists(html_path));
  const std::string html = ReadBytes(html_path);
  for (const char* id :
       {"overview", "losses", "beacons", "calibration", "rollouts", "teaching-time"}) {
    EXPECT_THAT(html, HasSubstr(std::string("id=\"") + id + "\"")) << id;
  }
  const std::regex external(R"((src|href)\s*=\s*["']?\s*(https?:)?//)", std::regex::icase);
  EXPECT_FALSE(std::regex_search(html, external)) << "the report links outside itself";
  EXPECT_THAT(html, HasSubstr("data:image/png;base64,"));
  int pngs = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(session / "report" / "figures")) {
    if (entry.path().extension() == ".png" && entry.file_size() > 0) ++pngs;
  }
  EXPECT_GT(pngs, 0);

  // The recipe's chunk length is recorded with each model, and --action-chunk overrides it; the
  // model rolls out with its own.
  const int recipe_chunk = ReadJson(session / "training" / "baseline.json")["action_chunk"];
  EXPECT_GE(recipe_chunk, 1);
  const int other_chunk = recipe_chunk + 2;
  r = RunRecon("train --session " + session.string() + " --methods baseline --steps 50 " +
               "--action-chunk " + std::to_string(other_chunk));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadJson(session / "training" / "baseline.json")["action_chunk"], other_chunk);
  r = RunRecon("eval --session " + session.string() + " --methods baseline --tests 1");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --action-chunk 0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--action-chunk"));

  // A learning rate the training cannot follow is the user's to lower, said as such; the models
  // trained before stay.
  const std::string baseline_model = ReadBytes(session / "checkpoints" / "baseline.ckpt");
  r = RunRecon("train --session " + session.string() + " --steps 20 --lr 10");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("try a lower learning rate (now 10) with --lr"));
  EXPECT_THAT(r.output, Not(HasSubstr("internal error")));
  EXPECT_EQ(ReadBytes(session / "checkpoints" / "baseline.ckpt"), baseline_model);
}

// The methods train side by side; each model is the one it would be trained alone.
TEST_F(SessionCliTest, MethodsTrainedTogetherAreTheModelsTrainedAlone) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world dynamic2d --seed 4 --demos 4 --play 20");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string train = "train --session " + session.string() + " --steps 150 --methods ";

  r = RunRecon(train + "baseline,baseline");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--methods: baseline is named twice"));
  EXPECT_FALSE(fs::exists(session / "checkpoints"));

  r = RunRecon(train + "baseline,recon");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("wrote " + session.string() + "/checkpoints/baseline.ckpt"));
  EXPECT_THAT(r.output, HasSubstr("wrote " + session.string() + "/checkpoints/recon.ckpt"));
  std::map<std::string, std::string> together;
  for (const char* method : {"baseline", "recon"}) {
    together[method] = ReadJson(session / "training" / (std::string(method) + ".json"))["model_id"];
  }
  EXPECT_NE(together["baseline"], together["recon"]);
  for (const char* method : {"recon", "baseline"}) {
    SCOPED_TRACE(method);
    r = RunRecon(train + method);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(ReadJson(session / "training" / (std::string(method) + ".json"))["model_id"],
              together[method]);
  }
}

// A simulated arm cell: calibrated on creation, or with a given calibration, or none.
TEST_F(SessionCliTest, BinTransferSessionCalibration) {
  const fs::path calibration = Path("calibration.json");
  constexpr int kPoints = 8;
  CommandResult r = RunRecon("calibrate --sim --points " + std::to_string(kPoints) +
                             " --seed 2 --out " + calibration.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const fs::path calibrated = Path("calibrated");
  r = Record(calibrated, "--world bintransfer --demos 1 --play 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json info = Info(calibrated);
  EXPECT_EQ(info["world"], "bintransfer");
  EXPECT_EQ(info["episodes"], 1);
  EXPECT_EQ(info["play"], 3);
  ASSERT_TRUE(info["calibration"].is_object()) << info.dump();
  EXPECT_GT(info["calibration"]["points"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(calibrated / "calibration.json"));

  const fs::path given = Path("given");
  r = Record(given, "--world bintransfer --demos 1 --calibration " + calibration.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  info = Info(given);
  ASSERT_TRUE(info["calibration"].is_object()) << info.dump();
  EXPECT_EQ(info["calibration"]["points"], kPoints);
  EXPECT_EQ(ReadBytes(given / "calibration.json"), ReadBytes(calibration));

  const fs::path none = Path("none");
  r = Record(none, "--world bintransfer --demos 1 --no-calibration");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Info(none)["calibration"].is_null());
  EXPECT_FALSE(fs::exists(none / "calibration.json"));
}

}  // namespace
