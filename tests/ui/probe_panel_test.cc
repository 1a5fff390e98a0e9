// The Rollouts step's "Check what it looks at" panel, headless: the button and why it is
// disabled, the progress and its cancel, and the results (verdicts, the table, a heat map per
// method of the object chosen), each state a golden and each control the command it sends; and
// the Record step's playback of a demonstration with the saliency over it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <variant>

#include "engine/core/error.h"
#include "tests/support/golden_image.h"
#include "tests/ui/probe_test_support.h"
#include "tests/ui/studio_harness.h"
#include "tests/ui/studio_test_support.h"

namespace recon::ui {
namespace {

using testing::Map;
using testing::Probed;
using testing::Progress;
using testing::SnapshotAt;

TEST(ProbePanelTest, ShowsWhatEachPolicyMovesWithAndSwitchesTheObjectShown) {
  StudioHarness harness;
  StudioSnapshot s = Probed();
  harness.Show(s);
  EXPECT_TRUE(
      ::recon::testing::MatchesGolden(harness.driver().Screenshot(), GoldenPath("rollouts_probe")));
  EXPECT_TRUE(harness.driver().Drawn("heat-map##0"));
  EXPECT_TRUE(harness.driver().Drawn("heat-map##1"));
  harness.Commands();
  EXPECT_THROW(harness.driver().Click("bowl##probe-object"), UserError);  // shown already
  harness.driver().Click("plate##probe-object");
  const std::optional<ShowProbeObject> shown = Last<ShowProbeObject>(harness.Commands());
  ASSERT_TRUE(shown.has_value());
  EXPECT_EQ(shown->object, "plate");
  harness.driver().Click("Check what it looks at");
  std::optional<RunProbe> run = Last<RunProbe>(harness.Commands());
  ASSERT_TRUE(run.has_value());
  EXPECT_FALSE(run->outcome);
  harness.driver().Click("...and roll out from every place");
  run = Last<RunProbe>(harness.Commands());
  ASSERT_TRUE(run.has_value());
  EXPECT_TRUE(run->outcome);
}

/// Where whole rollouts succeeded (1) with the object in each cell, failed (0), or were not
/// rolled out (NaN: overlap).
ProbeView::Map OutcomeMap(const std::string& label, float reach) {
  ProbeView::Map map = Map(label, 1.0f);
  for (size_t i = 0; i < map.values.size(); ++i) {
    if (std::isnan(map.values[i])) continue;
    const float x = 0.22f + (static_cast<float>(i % 10) + 0.5f) * 0.06f;
    map.values[i] = x < reach ? 1.0f : 0.0f;
  }
  map.scale_max = 1.0f;
  return map;
}

TEST(ProbePanelTest, WholeRolloutsShowWhereEachPolicyStillDoesTheTask) {
  StudioHarness harness;
  StudioSnapshot s = Probed();
  s.probe.rolled_out = true;
  const double rates[] = {0.3, 0.8, 0.9, 0.95, 0.85, 0.9};
  for (size_t i = 0; i < s.probe.rows.size(); ++i) s.probe.rows[i].success_rate = rates[i];
  s.probe.verdicts.push_back(
      "RECON (Play) succeeds from 95 % of the bowl's places, 85 % of the plate's places, 90 % "
      "of the toast's places");
  s.probe.outcome_maps = {OutcomeMap("Baseline", 0.4f), OutcomeMap("RECON (Play)", 0.75f)};
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("rollouts_probe_outcome")));
  EXPECT_TRUE(harness.driver().Drawn("outcome-map##0"));
  EXPECT_TRUE(harness.driver().Drawn("outcome-map##1"));
}

TEST(ProbePanelTest, ARealCellsSessionIsReadOutOnItsRecordedFrames) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kDone, teach::Step::kRollouts);
  s.cell_kind = "real";
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Check what it looks at"), UserError);  // nothing to move
  harness.Commands();
  harness.driver().Click("Read out what its features encode");
  const std::optional<RunProbe> run = Last<RunProbe>(harness.Commands());
  ASSERT_TRUE(run.has_value());
  EXPECT_FALSE(run->outcome);
}

TEST(ProbePanelTest, TheSaliencyToggleOverThePlaybackSendsTheModeChosen) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kDone, teach::Step::kRollouts);  // with the playback
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Off##saliency"), UserError);  // off already
  harness.Commands();
  harness.driver().Click("Gradient##saliency");
  std::optional<SetSaliency> set = Last<SetSaliency>(harness.Commands());
  ASSERT_TRUE(set.has_value());
  EXPECT_EQ(set->mode, SaliencyMode::kGradient);
  s.saliency = SaliencyMode::kOcclusion;
  harness.Show(s);
  harness.driver().Click("Off##saliency");
  set = Last<SetSaliency>(harness.Commands());
  ASSERT_TRUE(set.has_value());
  EXPECT_EQ(set->mode, SaliencyMode::kOff);
}

TEST(ProbePanelTest, RunsWithAProgressBarAndACancelAndSaysWhyItCannotRun) {
  StudioHarness harness;
  StudioSnapshot s = Probed();
  s.probe.running = true;
  s.probe.phase = "moving objects";
  s.probe.done = 120;
  s.probe.total = 300;
  s.busy_with = "the probe";
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("rollouts_probe_running")));
  harness.Commands();
  harness.driver().Click("Cancel the check");
  EXPECT_TRUE(Last<CancelProbe>(harness.Commands()).has_value());

  // Nothing trained: the button is there, disabled.
  s = SnapshotAt(Progress::kRecorded, teach::Step::kRollouts);
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Check what it looks at"), UserError);
  EXPECT_THROW(harness.driver().Click("...and roll out from every place"), UserError);
}

/// A 64 x 64 frame: a table-grey floor with a bright square where the saliency would be.
RgbImage Frame() {
  RgbImage image;
  image.width = image.height = 64;
  image.rgb.assign(64 * 64 * 3, 90);
  for (int r = 20; r < 34; ++r) {
    for (int c = 30; c < 44; ++c) {
      uint8_t* p = image.rgb.data() + (static_cast<size_t>(r) * 64 + c) * 3;
      p[0] = 250;
      p[1] = 220;
      p[2] = 40;
    }
  }
  return image;
}

TEST(EpisodePlayerTest, WatchesADemonstrationFrameByFrameWithTheSaliencyOfEachPolicy) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kDone, teach::Step::kRecord);
  ASSERT_FALSE(s.episodes.empty());
  harness.Show(s);
  EXPECT_FALSE(harness.driver().Drawn("Close##episode-playback"));  // nothing played back yet
  harness.Commands();
  const std::string first = s.episodes[0].name;
  harness.driver().Click(first + "##watch");
  std::optional<ShowEpisodeFrame> shown = Last<ShowEpisodeFrame>(harness.Commands());
  ASSERT_TRUE(shown.has_value());
  EXPECT_EQ(shown->episode, first);
  EXPECT_EQ(shown->frame, 0);

  EpisodePlaybackView& p = s.episode_playback;
  p.episode = first;
  p.frames = 120;
  p.frame = 41;
  p.method = "recon";
  p.methods = {{"baseline", "Baseline"}, {"recon", "RECON (Play)"}};
  p.image = Frame();
  p.image_frame = 1;
  s.saliency = SaliencyMode::kGradient;
  harness.Show(s);
  EXPECT_TRUE(::recon::testing::MatchesGolden(harness.driver().Screenshot(),
                                              GoldenPath("record_episode_saliency")));
  harness.Commands();
  harness.driver().Click(first + "##watch");  // shown already: nothing sent
  EXPECT_FALSE(Last<ShowEpisodeFrame>(harness.Commands()).has_value());
  harness.driver().Click("Baseline##episode-saliency");
  shown = Last<ShowEpisodeFrame>(harness.Commands());
  ASSERT_TRUE(shown.has_value());
  EXPECT_EQ(shown->method, "baseline");
  EXPECT_EQ(shown->frame, 41);  // the same step, the other policy's saliency
  harness.driver().Click("Off##saliency");
  const std::optional<SetSaliency> off = Last<SetSaliency>(harness.Commands());
  ASSERT_TRUE(off.has_value());
  EXPECT_EQ(off->mode, SaliencyMode::kOff);
  harness.driver().Click("Close##episode-playback");
  shown = Last<ShowEpisodeFrame>(harness.Commands());
  ASSERT_TRUE(shown.has_value());
  EXPECT_TRUE(shown->episode.empty());

  // Nothing trained: the frames play, and the screen says what a saliency needs.
  p.methods.clear();
  p.method.clear();
  harness.Show(s);
  EXPECT_THROW(harness.driver().Click("Gradient##saliency"), UserError);
  EXPECT_TRUE(harness.driver().Drawn("Close##episode-playback"));
}

}  // namespace
}  // namespace recon::ui
