#include "engine/experiments/condition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace recon::experiments {
namespace {

using ::testing::HasSubstr;

TEST(ConditionTest, DynamicDefaultsAreThePaperFigure) {
  const auto conditions =
      ParseConditions("dynamic2d", DefaultConditionNames("dynamic2d"), {2.5, 4.5, 6.5});
  ASSERT_EQ(conditions.size(), 10u);
  EXPECT_EQ(conditions[0].name, "baseline");
  EXPECT_EQ(conditions[0].method, learn::Method::kBaseline);
  EXPECT_EQ(conditions[0].placement, "none");
  EXPECT_EQ(conditions[7].name, "exact-sigma2.5");
  EXPECT_EQ(conditions[7].placement, "exact");
  EXPECT_DOUBLE_EQ(conditions[9].noise_sigma, 6.5);
}

TEST(ConditionTest, StaticPlayConditionsUsePlay) {
  const auto conditions = ParseConditions("static2d", {"recon-d-play", "recon-p"}, {});
  ASSERT_EQ(conditions.size(), 2u);
  EXPECT_TRUE(conditions[0].use_play);
  EXPECT_EQ(conditions[0].placement, "distance");
  EXPECT_FALSE(conditions[1].use_play);
  EXPECT_EQ(conditions[1].placement, "position");
}

TEST(ConditionTest, UnknownNameListsValidOnes) {
  try {
    ParseConditions("dynamic2d", {"exact", "exakt"}, {});
    FAIL();
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown condition 'exakt'"));
    EXPECT_THAT(e.what(), HasSubstr("exact+random"));
  }
}

TEST(ConditionTest, DuplicatesAndBadNoiseAreRejected) {
  EXPECT_THROW(ParseConditions("dynamic2d", {"exact", "exact"}, {}), UserError);
  EXPECT_THROW(ParseConditions("dynamic2d", {"exact"}, {-1.0}), UserError);
  EXPECT_THROW(ParseConditions("static2d", {"baseline"}, {2.5}), UserError);
  EXPECT_THROW(ParseConditions("dynamic3d", {"exact"}, {}), UserError);
  EXPECT_THROW(ParseConditions("dynamic2d", {}, {}), UserError);
}

}  // namespace
}  // namespace recon::experiments
