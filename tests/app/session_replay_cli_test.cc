// `recon eval` on a simulated arm session keeps a replay of every rollout beside its JSON, so
// the studio can play the Baseline and RECON back side by side, frame by frame.

#include <algorithm>

#include "engine/store/rollout_replay.h"
#include "engine/store/session.h"
#include "tests/app/session_cli_fixture.h"

namespace {

using namespace recon::session_cli_testing;  // NOLINT: the fixture and its helpers

// worlds::Tabletop::kEpisodeLength: rollouts run that many steps, and the replay keeps the state
// after the reset and after each step.
constexpr int kTabletopEpisodeLength = 200;

TEST_F(SessionCliTest, TabletopEvalWritesAReplayOfEveryRollout) {
  const fs::path session = Path("s");
  constexpr int kTests = 3;
  CommandResult r = Record(session, "--world tabletop --image-size 32 --seed 5 --demos 2 --play 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("train --session " + session.string() + " --methods baseline,recon --steps 20");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunRecon("eval --session " + session.string() + " --tests " + std::to_string(kTests));
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // A rollout runs the task's 20 s or 1.5 times the longest demonstration, whichever is longer.
  size_t longest = 0;
  {
    const recon::store::Session opened =
        recon::store::Session::Open(session.string(), recon::store::Session::Access::kReadOnly);
    for (const auto& e : opened.demos()) longest = std::max<size_t>(longest, e.meta.num_samples);
  }
  ASSERT_GT(longest, 0u);
  const size_t steps = std::max<size_t>(kTabletopEpisodeLength, (3 * longest + 1) / 2);
  for (const std::string method : {"baseline", "recon"}) {
    SCOPED_TRACE(method);
    const json rollout = ReadJson(session / "rollouts" / (method + ".json"));
    ASSERT_TRUE(rollout.contains("replay")) << rollout.dump();
    EXPECT_EQ(rollout["replay"], "rollouts/" + method + ".replay.h5");
    const fs::path replay_path = session / rollout["replay"].get<std::string>();
    ASSERT_TRUE(fs::exists(replay_path));
    const recon::store::RolloutReplay replay = recon::store::ReadRolloutReplay(replay_path);
    EXPECT_EQ(replay.world, "tabletop");
    EXPECT_EQ(replay.method, method);
    EXPECT_GT(replay.state_size, 0);
    ASSERT_EQ(replay.scenarios.size(), static_cast<size_t>(kTests));
    for (size_t i = 0; i < replay.scenarios.size(); ++i) {
      SCOPED_TRACE("scenario " + std::to_string(i));
      const recon::store::ScenarioReplay& scenario = replay.scenarios[i];
      EXPECT_EQ(scenario.states.size(), steps + 1);
      // The replay is of the very rollouts the JSON scores.
      const json& scored = rollout["per_scenario"][i];
      EXPECT_EQ(scenario.seed, scored["seed"].get<uint64_t>());
      EXPECT_DOUBLE_EQ(scenario.metric, scored["metric"].get<double>());
      EXPECT_EQ(scenario.succeeded, scored["succeeded"].get<bool>());
    }
  }
  // Nothing but the JSON and the replays (no temporary left behind).
  std::set<std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(session / "rollouts")) {
    files.insert(entry.path().filename().string());
  }
  EXPECT_EQ(files, (std::set<std::string>{"baseline.json", "baseline.replay.h5", "recon.json",
                                          "recon.replay.h5"}));
}

}  // namespace
