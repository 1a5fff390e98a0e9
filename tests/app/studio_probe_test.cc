// The studio's "Check what it looks at" on a real tabletop session (made and trained with the
// `recon` binary): the probe runs as a job with its progress, lands in the session and the
// Rollouts step, switches the object shown, a cancelled probe keeps the one from before, and on
// ask each policy is rolled out from every place; the saliency is laid over the rollout playback
// and taken off again.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "app/studio/studio_controller.h"
#include "tests/app/run_recon.h"
#include "tests/app/studio_twin_fixture.h"

namespace recon::studio {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::WaitFor;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class StudioProbeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("recon_studio_probe_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    for (const std::string& args :
         {"record --session " + Session().string() + " --world tabletop --demos 2 --seed 70",
          "train --session " + Session().string() + " --steps 30 --seed 3",
          "eval --session " + Session().string() + " --tests 1 --seed 11"}) {
      const recon::testing::CommandResult r = recon::testing::RunRecon(args);
      ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.output;
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Session() const { return dir_ / "session"; }
  StudioOptions Options() const {
    StudioOptions options;
    options.session_dir = Session().string();
    options.recent_sessions_file = (dir_ / "recent.json").string();
    options.dev_dir = (dir_ / "no-dev").string();
    return options;
  }
  fs::path dir_;
};

TEST_F(StudioProbeTest, TheSaliencyIsLaidOverThePlaybackAndTakenOffAgain) {
  StudioController controller(Options());
  controller.Push(ui::OpenStep{teach::Step::kRollouts});
  ui::StudioSnapshot s = WaitFor(controller, [](const auto& now) {
    return now.rollouts.size() == 2 && now.rollouts[0].has_replay &&
           !now.rollouts[0].frame_image.rgb.empty();
  });
  controller.Push(ui::ShowRolloutFrame{0, 5});
  s = WaitFor(controller, [](const auto& now) { return now.rollouts[0].frame == 5; });
  const RgbImage plain = s.rollouts[0].frame_image;
  for (const ui::SaliencyMode mode : {ui::SaliencyMode::kGradient, ui::SaliencyMode::kOcclusion}) {
    controller.Push(ui::SetSaliency{mode});
    s = WaitFor(controller, [&](const auto& now) {
      return now.saliency == mode && now.rollouts[0].frame_image.rgb != plain.rgb;
    });
    EXPECT_EQ(s.rollouts[0].frame_image.width, plain.width);
  }
  controller.Push(ui::SetSaliency{ui::SaliencyMode::kOff});
  s = WaitFor(controller, [&](const auto& now) {
    return now.saliency == ui::SaliencyMode::kOff && now.rollouts[0].frame_image.rgb == plain.rgb;
  });
  EXPECT_TRUE(s.errors.empty());
}

TEST_F(StudioProbeTest, ARecordedDemonstrationPlaysBackWithEachPolicysSaliencyOverIt) {
  StudioController controller(Options());
  ui::StudioSnapshot s = WaitFor(
      controller, [](const auto& now) { return now.session_open && now.episodes.size() == 2; });
  const int samples = s.episodes[0].samples;
  controller.Push(ui::OpenStep{teach::Step::kRecord});
  controller.Push(ui::ShowEpisodeFrame{"demo_0", 5, ""});
  s = WaitFor(controller, [](const auto& now) { return now.episode_playback.frames > 0; });
  const ui::EpisodePlaybackView& p = s.episode_playback;
  EXPECT_EQ(p.episode, "demo_0");
  EXPECT_EQ(p.frames, samples);
  EXPECT_EQ(p.frame, 5);
  EXPECT_EQ(p.method, "baseline");  // the first trained one
  ASSERT_EQ(p.methods.size(), 2u);
  EXPECT_EQ(p.methods[1].second, "RECON");
  ASSERT_EQ(p.image.width, 64);
  const RgbImage plain = p.image;

  // The saliency on: the frame is drawn again with the Baseline's map over it, then RECON's.
  controller.Push(ui::SetSaliency{ui::SaliencyMode::kGradient});
  s = WaitFor(controller,
              [&](const auto& now) { return now.episode_playback.image.rgb != plain.rgb; });
  const RgbImage baseline = s.episode_playback.image;
  controller.Push(ui::ShowEpisodeFrame{"demo_0", 5, "recon"});
  s = WaitFor(controller, [](const auto& now) { return now.episode_playback.method == "recon"; });
  EXPECT_NE(s.episode_playback.image.rgb, baseline.rgb);
  EXPECT_NE(s.episode_playback.image.rgb, plain.rgb);
  // Past the end: the last frame.
  controller.Push(ui::ShowEpisodeFrame{"demo_0", 100000, ""});
  s = WaitFor(controller,
              [&](const auto& now) { return now.episode_playback.frame == samples - 1; });
  EXPECT_EQ(s.episode_playback.method, "recon");  // kept

  // Bad requests are refused by name; the playback stays as it was.
  controller.Push(ui::ShowEpisodeFrame{"demo_9", 0, ""});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors.back(), HasSubstr("demo_9"));
  EXPECT_EQ(s.episode_playback.episode, "demo_0");
  controller.Push(ui::DismissErrors{});
  WaitFor(controller, [](const auto& now) { return now.errors.empty(); });
  controller.Push(ui::ShowEpisodeFrame{"demo_0", 0, "bc"});
  s = WaitFor(controller, [](const auto& now) { return !now.errors.empty(); });
  EXPECT_THAT(s.errors.back(), HasSubstr("bc is not trained"));

  // Deleting the episode shown closes the playback.
  controller.Push(ui::DeleteEpisode{"demo_0"});
  s = WaitFor(controller, [](const auto& now) { return now.episode_playback.episode.empty(); });
  EXPECT_EQ(s.episode_playback.frames, 0);
}

TEST_F(StudioProbeTest, RunsAsAJobAndShowsWhatEachPolicyLooksAt) {
  StudioOptions options = Options();
  options.probe_grid = 4;  // --probe-grid 4: sixteen places per object
  auto studio = std::make_unique<StudioController>(options);
  StudioController& controller = *studio;
  ui::StudioSnapshot s = WaitFor(
      controller, [](const auto& now) { return now.session_open && !now.training.empty(); });
  EXPECT_FALSE(s.probe.present);
  controller.Push(ui::OpenStep{teach::Step::kRollouts});
  controller.Push(ui::RunProbe{});
  s = WaitFor(controller, [](const auto& now) { return now.probe.running && now.probe.total > 0; });
  EXPECT_EQ(s.busy_with, "the probe");
  EXPECT_LE(s.probe.done, s.probe.total);
  s = WaitFor(
      controller, [](const auto& now) { return !now.probe.running && now.probe.present; }, 120);
  ASSERT_TRUE(s.errors.empty()) << s.errors.back();
  EXPECT_THAT(s.status, HasSubstr("Checked what the policies look at"));
  EXPECT_EQ(s.probe.rows.size(), 6u);      // two methods, three objects
  ASSERT_EQ(s.probe.verdicts.size(), 4u);  // per method: what it moves with, what it encodes
  EXPECT_THAT(s.probe.verdicts[0], HasSubstr("moves most with the"));
  EXPECT_THAT(s.probe.verdicts[1], HasSubstr("features encode"));
  EXPECT_FALSE(s.probe.rolled_out);
  EXPECT_EQ(s.probe.objects, (std::vector<std::string>{"bowl", "plate", "toast"}));
  EXPECT_EQ(s.probe.shown_object, "bowl");
  ASSERT_EQ(s.probe.maps.size(), 2u);
  EXPECT_EQ(s.probe.maps[0].values.size(), 16u);
  EXPECT_TRUE(fs::exists(Session() / "probe" / "probe.json"));
  EXPECT_TRUE(s.probe.out_of_date.empty());

  controller.Push(ui::ShowProbeObject{"plate"});
  s = WaitFor(controller, [](const auto& now) { return now.probe.shown_object == "plate"; });
  EXPECT_EQ(s.probe.maps.size(), 2u);

  // A cancelled probe writes nothing: the session keeps the one from before.
  const std::string before = ReadText(Session() / "probe" / "probe.json");
  controller.Push(ui::RunProbe{});
  controller.Push(ui::CancelProbe{});
  s = WaitFor(controller, [](const auto& now) {
    return !now.probe.running && now.status.find("cancelled") != std::string::npos;
  });
  EXPECT_EQ(ReadText(Session() / "probe" / "probe.json"), before);

  // On ask, each policy is also rolled out whole from every place.
  controller.Push(ui::RunProbe{true});
  s = WaitFor(controller, [](const auto& now) {
    return now.probe.running && now.probe.phase == "rolling out from each place";
  });
  EXPECT_LE(s.probe.done, s.probe.total);
  s = WaitFor(
      controller, [](const auto& now) { return !now.probe.running && now.probe.rolled_out; }, 120);
  ASSERT_TRUE(s.errors.empty()) << s.errors.back();
  ASSERT_EQ(s.probe.rows.size(), 6u);
  for (const ui::ProbeView::Row& row : s.probe.rows) {
    ASSERT_TRUE(row.success_rate.has_value()) << row.label << " " << row.object;
    EXPECT_GE(*row.success_rate, 0.0);
    EXPECT_LE(*row.success_rate, 1.0);
  }
  ASSERT_EQ(s.probe.outcome_maps.size(), 2u);
  for (const ui::ProbeView::Map& map : s.probe.outcome_maps) {
    ASSERT_EQ(map.values.size(), 16u);
    EXPECT_EQ(map.scale_max, 1.0f);
    for (float v : map.values) EXPECT_TRUE(std::isnan(v) || v == 0.0f || v == 1.0f) << v;
  }
  EXPECT_THAT(s.probe.note, HasSubstr("4 x 4 grid"));
  EXPECT_THAT(s.probe.note, HasSubstr("Whole rollouts"));

  // Retraining a method (the studio closed: it holds the session) makes the probe out of date.
  studio.reset();
  const recon::testing::CommandResult r = recon::testing::RunRecon(
      "train --session " + Session().string() + " --methods recon --steps 20 --seed 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  StudioController reopened(Options());
  s = WaitFor(reopened, [](const auto& now) { return now.probe.present; });
  EXPECT_THAT(s.probe.out_of_date, HasSubstr("RECON retrained"));
}

}  // namespace
}  // namespace recon::studio
