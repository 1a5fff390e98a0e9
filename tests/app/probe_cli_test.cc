// `recon eval --probe`: what a session's trained methods look at, through the real binary on a
// real tabletop session (MuJoCo, EGL, trained models): the numbers as text and as the JSON the
// issue names, the heat maps in the session, and every bad input refused by name with nothing
// written.

#include "tests/app/session_cli_fixture.h"

namespace recon::session_cli_testing {
namespace {

constexpr char kPng[] = "\x89PNG";

TEST_F(SessionCliTest, ProbePrintsWhatEachMethodLooksAtAndKeepsItsHeatMaps) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world tabletop --demos 2 --play 10 --seed 70");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --steps 30 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  r = RunRecon("eval --session " + session.string() +
               " --probe --grid 4 --readout-scenes 12 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json printed = ParseJsonOutput(r);
  ASSERT_TRUE(printed.contains("methods")) << r.output;
  for (const char* method : {"baseline", "recon"}) {
    ASSERT_TRUE(printed["methods"].contains(method)) << printed.dump(1);
    for (const char* object : {"bowl", "plate", "toast"}) {
      const json& o = printed["methods"][method][object];
      ASSERT_TRUE(o.is_object()) << method << " " << object;
      EXPECT_TRUE(o["action_change_per_10cm"].is_number());
      EXPECT_GE(o["action_change_per_10cm"].get<double>(), 0.0);
      EXPECT_TRUE(o["feature_change_per_10cm"].is_number());
      // The toast waits at one place in every scene: nothing to read out.
      if (std::string(object) == "toast") {
        EXPECT_TRUE(o["readout_r2"].is_null());
      } else {
        EXPECT_TRUE(o["readout_r2"].is_number());
      }
      const fs::path figure = session / o["figure"].get<std::string>();
      EXPECT_EQ(ReadBytes(figure).substr(0, 4), kPng) << figure;
    }
  }
  EXPECT_EQ(printed["grid"]["nx"], 4);
  EXPECT_EQ(printed["readout"]["scenes"], 12);
  // The session keeps what was printed.
  EXPECT_EQ(ReadJson(session / "probe" / "probe.json")["methods"], printed["methods"]);

  // As text: a row per method and object, and where the numbers went.
  r = RunRecon("eval --session " + session.string() + " --probe --grid 3 --object bowl");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("RECON (Play)"));
  EXPECT_THAT(r.output, HasSubstr("bowl"));
  EXPECT_THAT(r.output, HasSubstr("3 x 3 grid"));
  EXPECT_THAT(r.output, HasSubstr("moving objects"));  // the progress line
  EXPECT_THAT(r.output, HasSubstr("probe.json"));
}

TEST_F(SessionCliTest, ProbeWithOutcomeRollsEachMethodOutFromEveryPlace) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world tabletop --demos 2 --seed 70");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --steps 20 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("eval --session " + session.string() +
               " --probe --grid 3 --object bowl --outcome --readout-scenes 8 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json printed = ParseJsonOutput(r);
  for (const char* method : {"baseline", "recon"}) {
    const json& bowl = printed["methods"][method]["bowl"];
    ASSERT_TRUE(bowl["outcome"].is_array()) << printed.dump(1);
    ASSERT_EQ(bowl["outcome"].size(), 9u);
    // The share is of the places rolled out from (null: not rolled out there).
    int rolled = 0, succeeded = 0;
    for (const json& v : bowl["outcome"]) {
      if (v.is_null()) continue;
      ++rolled;
      EXPECT_TRUE(v == 0.0 || v == 1.0) << v;
      succeeded += v == 1.0 ? 1 : 0;
    }
    ASSERT_GT(rolled, 0);
    EXPECT_DOUBLE_EQ(bowl["success_rate"].get<double>(), static_cast<double>(succeeded) / rolled);
    EXPECT_TRUE(bowl["home_succeeded"].is_boolean());
    const fs::path figure = session / bowl["outcome_figure"].get<std::string>();
    EXPECT_EQ(ReadBytes(figure).substr(0, 4), kPng) << figure;
  }
  r = RunRecon("eval --session " + session.string() + " --probe --grid 2 --object bowl --outcome");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("rolling out from each place"));  // the progress line
  EXPECT_THAT(r.output, HasSubstr("succeeded"));
  EXPECT_THAT(r.output, HasSubstr("of the bowl's places"));
}

TEST_F(SessionCliTest, ARealCellsSessionIsReadOutOnItsRecordedFramesAndMovesNothing) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world tabletop --demos 4 --play 40 --seed 70");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --steps 30 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The manifest now says a real cell recorded it: RECON Studio cannot simulate that cell.
  json manifest = ReadJson(session / "session.json");
  manifest["cell"]["kind"] = "real";
  std::ofstream(session / "session.json") << manifest.dump(2);

  const std::string probe = "eval --session " + session.string() + " --probe ";
  for (const char* moving : {"--grid 4", "--object bowl", "--outcome", "--readout-scenes 20"}) {
    r = RunRecon(probe + moving);
    EXPECT_NE(r.exit_code, 0) << moving;
    EXPECT_THAT(r.output, HasSubstr(std::string(moving).substr(0, std::string(moving).find(' '))));
    EXPECT_THAT(r.output, HasSubstr("cannot simulate"));
    EXPECT_FALSE(fs::exists(session / "probe")) << moving;
  }
  r = RunRecon(probe + "--json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json printed = ParseJsonOutput(r);
  EXPECT_GT(printed["readout"]["recorded_frames"].get<int>(), 100);
  EXPECT_EQ(printed["readout"]["recorded_episodes"].get<int>(), 4 + 4);  // 4 demos, 4 play chunks
  for (const char* method : {"baseline", "recon"}) {
    const json& methods = printed["methods"][method];
    ASSERT_EQ(methods.size(), 1u) << methods.dump(1);  // the one beacon's object
    const json& plate = methods["plate"];
    EXPECT_TRUE(plate["readout_r2"].is_number()) << plate.dump();
    EXPECT_LE(plate["readout_r2"].get<double>(), 1.0);
    EXPECT_TRUE(plate["action_change_per_10cm"].is_null());
    EXPECT_TRUE(plate["figure"].is_null());
  }
  r = RunRecon(probe);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("recorded frames of 8 episodes"));
  EXPECT_THAT(r.output, HasSubstr("features encode"));
  EXPECT_THAT(r.output, Not(HasSubstr("heat maps")));
}

/// A PNG's width and height from its IHDR chunk.
std::pair<uint32_t, uint32_t> PngSize(const std::string& bytes) {
  const auto word = [&](size_t at) {
    return (uint32_t(uint8_t(bytes[at])) << 24) | (uint32_t(uint8_t(bytes[at + 1])) << 16) |
           (uint32_t(uint8_t(bytes[at + 2])) << 8) | uint32_t(uint8_t(bytes[at + 3]));
  };
  return {word(16), word(20)};
}

TEST_F(SessionCliTest, SaliencyDrawsWhatDrivesEachActionOverARecordedDemonstration) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world tabletop --demos 2 --seed 70");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --steps 20 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("eval --session " + session.string() + " --saliency demo_1 --frames 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("rows: recorded; Baseline; RECON"));
  const std::string png = ReadBytes(session / "probe" / "saliency_demo_1.png");
  ASSERT_EQ(png.substr(0, 4), kPng);
  // 3 frames of 64 x 64 drawn 3x across, 4 px apart; a row for the frames and one per method.
  EXPECT_EQ(PngSize(png), (std::pair<uint32_t, uint32_t>{3 * 192 + 4 * 4, 3 * 192 + 4 * 4}));
  r = RunRecon("eval --session " + session.string() +
               " --saliency demo_0 --occlusion --frames 2 --method recon");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("occlusion saliency over demo_0"));
  EXPECT_EQ(PngSize(ReadBytes(session / "probe" / "saliency_demo_0.png")),
            (std::pair<uint32_t, uint32_t>{2 * 192 + 3 * 4, 2 * 192 + 3 * 4}));

  const std::string saliency = "eval --session " + session.string() + " --saliency ";
  const struct {
    std::string args, words;
  } cases[] = {
      {saliency + "demo_9", "no demonstration \"demo_9\" (valid: demo_0, demo_1)"},
      {saliency + "demo_0 --frames 0", "--frames"},
      {saliency + "demo_0 --probe", "--probe"},
      {"eval --session " + session.string() + " --occlusion", "--saliency"},
  };
  for (const auto& c : cases) {
    r = RunRecon(c.args);
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_THAT(r.output, HasSubstr(c.words)) << c.args;
  }
  EXPECT_FALSE(fs::exists(session / "probe" / "saliency_demo_9.png"));
}

TEST_F(SessionCliTest, ProbeRefusesBadInputByNameAndWritesNothing) {
  const fs::path session = Path("s");
  CommandResult r = Record(session, "--world tabletop --demos 2 --seed 70");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string probe = "eval --session " + session.string() + " --probe ";
  // Nothing trained yet.
  r = RunRecon(probe);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("no trained method to probe"));
  r = RunRecon("train --session " + session.string() + " --methods baseline --steps 20");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const struct {
    std::string args, words;
  } cases[] = {
      {probe + "--method recon", "recon is not trained"},
      {probe + "--object cup", "no object \"cup\" (valid: bowl, plate, toast)"},
      {probe + "--grid 1", "--grid"},
      {probe + "--readout-scenes 4", "--readout-scenes"},
      {probe + "--tests 5", "--tests"},
      {"eval --session " + session.string() + " --object bowl", "--probe"},
      {"eval --session " + session.string() + " --json", "--probe"},
      {"eval --session " + session.string() + " --outcome", "--probe"},
  };
  for (const auto& c : cases) {
    r = RunRecon(c.args);
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_THAT(r.output, HasSubstr(c.words)) << c.args;
    EXPECT_FALSE(fs::exists(session / "probe")) << c.args;
  }
}

}  // namespace
}  // namespace recon::session_cli_testing
