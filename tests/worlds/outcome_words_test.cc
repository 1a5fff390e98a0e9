// A failed test scene is named by the first thing that went wrong in it, in a teacher's words.

#include "engine/worlds/outcome_words.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace recon::worlds {
namespace {

std::map<std::string, double> Details(double grasped, double held, double bowl, double nothing) {
  return {{"grasped", grasped},
          {"toast_held", held},
          {"grip_nearer_bowl", bowl},
          {"closes_on_nothing", nothing},
          {"toast_moved", grasped}};
}

TEST(OutcomeWordsTest, EachFailureIsNamedByWhatWentWrongFirst) {
  EXPECT_EQ(DescribeFailure(Details(0, 0, 0, 0), false), "never picked the toast up");
  EXPECT_EQ(DescribeFailure(Details(0, 0, 1, 2), false),
            "closed the gripper on nothing, never held the toast");
  EXPECT_EQ(DescribeFailure(Details(1, 1, 1, 0), false), "kept holding the toast to the end");
  EXPECT_EQ(DescribeFailure(Details(1, 0, 1, 0), false), "delivered towards the bowl");
  EXPECT_EQ(DescribeFailure(Details(1, 0, 0, 0), false), "let the toast go off the plate");
  // How far off, where the world says.
  std::map<std::string, double> off = Details(1, 0, 0, 0);
  off["toast_to_plate_m"] = 0.137;
  EXPECT_EQ(DescribeFailure(off, false), "let the toast go off the plate, 14 cm from its middle");
  // Fallen off the table comes before where the gripper ended.
  off["toast_off_table"] = 1;
  off["grip_nearer_bowl"] = 1;
  EXPECT_EQ(DescribeFailure(off, false), "dropped the toast off the table");
}

TEST(OutcomeWordsTest, SuccessesAndWorldsWithoutAGraspSayNothing) {
  EXPECT_EQ(DescribeFailure(Details(1, 0, 0, 0), true), "");
  EXPECT_EQ(DescribeFailure({}, false), "");                   // a 2-D world
  EXPECT_EQ(DescribeFailure({{"distance", 0.3}}, false), "");  // details without a grasp
}

}  // namespace
}  // namespace recon::worlds
