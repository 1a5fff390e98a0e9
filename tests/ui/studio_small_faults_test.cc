// Faults a person met on the screens, each with the test that would have caught it: a
// demonstration's row plays it when clicked anywhere but its buttons, the window's close button
// asks before it stops what runs, and the Play data screen says what really moves.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <variant>

#include "tests/ui/studio_harness.h"
#include "tests/ui/studio_test_support.h"
#include "ui/screens/screens.h"
#include "ui/widgets/widget_registry.h"

namespace recon::ui {
namespace {

using testing::Progress;
using testing::SnapshotAt;

// The row plays, not only its name's text: a click in its "Done" cell shows it.
TEST(RecordListTest, ADemonstrationsWholeRowPlaysIt) {
  StudioHarness harness;
  harness.Show(SnapshotAt(Progress::kRecorded, teach::Step::kRecord));
  harness.Commands();
  const std::optional<WidgetRect> name = WidgetRegistry::ForThisThread().Find("demo_1##watch");
  const std::optional<WidgetRect> del = WidgetRegistry::ForThisThread().Find("Delete##demo_1");
  ASSERT_TRUE(name.has_value());
  ASSERT_TRUE(del.has_value());
  // In the "Done" column: right of the name's cell, left of the buttons.
  harness.driver().ClickAt(del->min_x - 20, del->CentreY());
  const std::optional<ShowEpisodeFrame> shown = Last<ShowEpisodeFrame>(harness.Commands());
  ASSERT_TRUE(shown.has_value()) << "a click on the row away from its name played nothing";
  EXPECT_EQ(shown->episode, "demo_1");
  // Its buttons still do their own work over the row.
  harness.driver().Click("Delete##demo_1");
  const std::vector<StudioCommand> commands = harness.Commands();
  EXPECT_TRUE(Last<DeleteEpisode>(commands).has_value());
  EXPECT_FALSE(Last<ShowEpisodeFrame>(commands).has_value());
}

// The close button pressed while a training runs: a question, keep it or stop it and close,
// each answer sent as it is chosen; nothing while the question is not asked.
TEST(CloseQuestionTest, ClosingWhileTrainingAsksFirst) {
  StudioHarness harness;
  StudioSnapshot training = SnapshotAt(Progress::kTrained, teach::Step::kTrain);
  training.training_running = true;
  training.busy_with = "the training";
  harness.Show(training);
  EXPECT_FALSE(harness.driver().Drawn("Stop the training and close##stop-and-close"));
  training.close_requested = true;
  harness.Show(training);
  harness.Commands();
  harness.driver().Click("Keep the training running##keep-running");
  std::optional<AnswerClose> answer = Last<AnswerClose>(harness.Commands());
  ASSERT_TRUE(answer.has_value());
  EXPECT_FALSE(answer->close);
  harness.driver().Click("Stop the training and close##stop-and-close");
  answer = Last<AnswerClose>(harness.Commands());
  ASSERT_TRUE(answer.has_value());
  EXPECT_TRUE(answer->close);
  training.close_requested = false;  // answered: the question goes
  harness.Show(training);
  EXPECT_FALSE(harness.driver().Drawn("Stop the training and close##stop-and-close"));
}

// A training the studio's closing cut short is said on the Train screen of the reopened session.
TEST(CloseQuestionTest, ATrainingCutShortIsSaidOnTheTrainScreen) {
  StudioHarness harness;
  StudioSnapshot s = SnapshotAt(Progress::kTrained, teach::Step::kTrain);
  harness.Show(s);
  EXPECT_FALSE(harness.driver().Drawn("training-cut-short"));
  s.training_cut_short =
      "The training of Baseline and RECON, started 2025-01-31 14:02, was cut "
      "short when the studio closed";
  harness.Show(s);
  EXPECT_TRUE(harness.driver().Drawn("training-cut-short"));
}

// The Play data screen says what the simulated cell does: the bowl moves within a scene, and
// each chunk's new scene moves the plate and its beacon (it said the plate stays).
TEST(PlayDataTest, ThePlayScreenSaysThePlateMovesWithEachScene) {
  StudioSnapshot s = SnapshotAt(Progress::kRecorded, teach::Step::kPlay);
  s.play_scene_samples = 10;
  const std::string said = PlayDataHowTo(s);
  EXPECT_EQ(said.find("stay"), std::string::npos) << said;
  EXPECT_NE(said.find("every 10 samples a new scene puts the plate"), std::string::npos) << said;
  s.studio_cell = "real";
  EXPECT_NE(PlayDataHowTo(s).find("by hand"), std::string::npos);
}

}  // namespace
}  // namespace recon::ui
