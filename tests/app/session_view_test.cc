// The step list's "next" follows the docs' advice: Record until the world's protocol has its
// demonstrations (four on the tabletop), though Train opens from the first.

#include "app/studio/session_view.h"

#include <gtest/gtest.h>

#include "engine/teach/workflow.h"

namespace recon::studio {
namespace {

teach::WorkflowFacts RecordedFacts(int demos) {
  teach::WorkflowFacts f;
  f.session_open = true;
  f.cell_connected = true;
  f.beacons_required = 1;
  f.beacons_assigned = 1;
  f.calibration_present = true;
  f.calibration_passed = true;
  f.demos = demos;
  f.demo_seconds = 13.0 * demos;
  return f;
}

TEST(SessionViewTest, TheNextStepStaysRecordUntilTheSuggestedDemonstrationsAreKept) {
  ui::StudioSnapshot s;
  ShowWorkflow(RecordedFacts(1), s, 4);
  EXPECT_EQ(s.next_step, teach::Step::kRecord);
  EXPECT_TRUE(s.can_open[static_cast<int>(teach::Step::kTrain)]) << "Train stays open";
  EXPECT_NE(s.steps[static_cast<int>(teach::Step::kRecord)].summary.find("4 suggested"),
            std::string::npos)
      << s.steps[static_cast<int>(teach::Step::kRecord)].summary;

  ShowWorkflow(RecordedFacts(4), s, 4);
  EXPECT_EQ(s.next_step, teach::Step::kTrain);

  // A world that asks for one: the first demonstration leads to Train.
  ShowWorkflow(RecordedFacts(1), s, 1);
  EXPECT_EQ(s.next_step, teach::Step::kTrain);

  // Before Record opens, the earlier steps come first.
  teach::WorkflowFacts uncalibrated = RecordedFacts(0);
  uncalibrated.calibration_present = uncalibrated.calibration_passed = false;
  ShowWorkflow(uncalibrated, s, 4);
  EXPECT_EQ(s.next_step, teach::Step::kCalibrate);
}

}  // namespace
}  // namespace recon::studio
