// A person's pauses (commands that move nothing and change nothing) are found and left out; a
// move, a gripper change and the samples around them are kept.

#include "engine/core/pauses.h"

#include <gtest/gtest.h>

namespace recon {
namespace {

// One motion entry and one gripper command (not motion).
const std::vector<float> kMotion = {1.0f, 0.0f};

Sample At(float u, float gripper) { return {{0.0f}, {}, {}, {u, gripper}}; }

TEST(Pauses, CommandsThatMoveNothingAndChangeNothingArePauses) {
  Episode e;
  e.samples = {At(0.0f, 0),   // looking before the first move: a pause
               At(0.1f, 0),   // moving
               At(0.0f, 0),   // stopped: a pause
               At(0.0f, 0),   // still stopped
               At(0.0f, 1),   // the gripper closes: kept
               At(0.0f, 1),   // waiting for it: a pause
               At(-0.1f, 1),  // moving again
               At(0.0f, 0)};  // letting go, standing: kept (the gripper changed)
  const bool expected[] = {true, false, true, true, false, true, false, false};
  for (size_t t = 0; t < e.samples.size(); ++t) {
    EXPECT_EQ(IsPause(e, t, kMotion), expected[t]) << "sample " << t;
  }
  EXPECT_FALSE(IsPause(e, 8, kMotion));  // past the end
  // With every entry motion, the gripper's change is a command too: only all-zero actions.
  EXPECT_FALSE(IsPause(e, 4, {}));
  EXPECT_FALSE(IsPause(e, 5, {}));

  Dataset d;
  d.spec.x_dim = 1;
  d.spec.u_dim = 2;
  d.demos = {e, e};
  d.play = {{{0.0f}, {}, {}}};
  d.play_chunks = {1};
  int64_t dropped = -1;
  const Dataset kept = WithoutPauses(d, kMotion, &dropped);
  EXPECT_EQ(dropped, 8);
  ASSERT_EQ(kept.demos.size(), 2u);
  ASSERT_EQ(kept.demos[0].samples.size(), 4u);
  EXPECT_EQ(kept.demos[0].samples[1].u, (std::vector<float>{0.0f, 1.0f}));
  EXPECT_EQ(kept.play.size(), 1u);
  EXPECT_EQ(kept.play_chunks, d.play_chunks);
}

TEST(Pauses, OnlyTheDemonstrationsNamedLoseTheirPauses) {
  Episode e;
  e.samples = {At(0.1f, 0), At(0.0f, 0), At(0.0f, 0)};
  Dataset d;
  d.demos = {e, e};
  int64_t dropped = 0;
  const Dataset kept = WithoutPauses(d, kMotion, &dropped, {true, false});
  EXPECT_EQ(dropped, 2);
  EXPECT_EQ(kept.demos[0].samples.size(), 1u);
  EXPECT_EQ(kept.demos[1].samples.size(), 3u);
}

TEST(Pauses, ATakeOfNothingButPausesKeepsItsFirstSample) {
  Dataset d;
  Episode e;
  e.samples = {At(0.0f, 0), At(0.0f, 0)};
  d.demos = {e};
  const Dataset kept = WithoutPauses(d, kMotion);
  ASSERT_EQ(kept.demos.size(), 1u);
  EXPECT_EQ(kept.demos[0].samples.size(), 1u);
}

}  // namespace
}  // namespace recon
