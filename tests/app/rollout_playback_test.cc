// The studio's rollout playback on replay files written as `recon eval` writes them: both
// methods' rollouts of one scene, stepped, clamped, played at the control rate and drawn through
// the real renderer.

#include "app/studio/rollout_playback.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/cli/session_world.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/store/rollout_replay.h"
#include "engine/teach/session_setup.h"
#include "engine/worlds/tabletop.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class RolloutPlaybackTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("recon-playback-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "rollouts");
    teach::SessionSetup setup;
    setup.world_name = "tabletop";
    setup.placement = "plate";
    setup.image_size = 64;
    store::SessionManifest probe;
    probe.world = "tabletop";
    probe.image_size = 64;
    manifest_ = teach::NewSessionManifest(setup, *cli::MakeSessionWorld(probe, "plate"));
    // Three scenes of five steps each, from real tabletop states: the expert moving the arm.
    auto world = cli::MakeSessionWorld(manifest_, "none");
    for (const char* method : {"baseline", "recon"}) {
      store::RolloutReplay replay;
      replay.world = "tabletop";
      replay.method = method;
      for (int scene = 0; scene < 3; ++scene) {
        store::ScenarioReplay s;
        s.seed = 100 + scene;
        s.metric = 0.1 * scene;
        s.succeeded = scene == 1;
        world->Reset(s.seed);
        for (int t = 0; t < 5; ++t) {
          s.states.push_back(world->ReplayState());
          world->Step(world->ExpertAction());
        }
        replay.scenarios.push_back(s);
      }
      replay.state_size = static_cast<int>(replay.scenarios[0].states[0].size());
      store::WriteRolloutReplay((dir_ / "rollouts" / (std::string(method) + ".replay.h5")).string(),
                                replay);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<ui::RolloutView> Views() const {
    std::vector<ui::RolloutView> views(2);
    views[0].method = "baseline";
    views[1].method = "recon";
    return views;
  }

  fs::path dir_;
  store::SessionManifest manifest_;
};

TEST_F(RolloutPlaybackTest, StepsClampsPlaysAndDrawsBothMethodsOnTheSameScene) {
  RolloutPlayback playback(manifest_, dir_.string());
  playback.Reload();
  const auto renderer = render::MujocoRendererFactory()();
  std::vector<ui::RolloutView> views = Views();
  playback.Fill(views, *renderer, 320, 240);
  for (const ui::RolloutView& v : views) {
    EXPECT_TRUE(v.has_replay);
    EXPECT_EQ(v.scenario, 0);
    EXPECT_EQ(v.frame, 0);
    EXPECT_EQ(v.frames, 5);
    EXPECT_EQ(v.scenario_seed, 100u);
    EXPECT_EQ(v.frame_image.width, 320);
    EXPECT_EQ(v.frame_image.height, 240);
  }
  const RgbImage first = views[0].frame_image;

  playback.Show(1, 3);
  views = Views();
  playback.Fill(views, *renderer, 320, 240);
  EXPECT_EQ(views[0].scenario, 1);
  EXPECT_EQ(views[1].frame, 3);
  EXPECT_TRUE(views[0].scenario_succeeded);
  EXPECT_NE(views[0].frame_image.rgb, first.rgb) << "another scene, another picture";
  // Both methods replay the same scene here (the same states): the same picture.
  EXPECT_EQ(views[0].frame_image.rgb, views[1].frame_image.rgb);

  playback.Show(99, 99);  // clamped to the last scene and step
  views = Views();
  playback.Fill(views, *renderer, 320, 240);
  EXPECT_EQ(views[0].scenario, 2);
  EXPECT_EQ(views[0].frame, 4);

  // Playing from the last step starts over, advances one step per 100 ms and stops at the end.
  const auto now = std::chrono::steady_clock::now();
  playback.SetPlaying(true, now);
  EXPECT_TRUE(playback.playing());
  views = Views();
  playback.Fill(views, *renderer, 320, 240);
  EXPECT_EQ(views[0].frame, 0);
  playback.Tick(now);  // too early
  views = Views();
  playback.Fill(views, *renderer, 320, 240);
  EXPECT_EQ(views[0].frame, 0);
  for (int i = 1; i <= 6; ++i) playback.Tick(now + std::chrono::milliseconds(150 * i));
  views = Views();
  playback.Fill(views, *renderer, 320, 240);
  EXPECT_EQ(views[0].frame, 4);
  EXPECT_FALSE(playback.playing());
}

TEST_F(RolloutPlaybackTest, ADamagedReplayFileIsNamed) {
  { std::ofstream(dir_ / "rollouts" / "recon.replay.h5", std::ios::trunc) << "not hdf5"; }
  RolloutPlayback playback(manifest_, dir_.string());
  try {
    playback.Reload();
    FAIL() << "a damaged replay was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("recon.replay.h5"));
  }
}

}  // namespace
}  // namespace recon::studio
