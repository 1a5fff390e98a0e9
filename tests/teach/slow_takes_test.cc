// Slow takes pointed out before training (teach::SlowTakesWarning).

#include "engine/teach/slow_takes.h"

#include <gtest/gtest.h>

namespace recon::teach {
namespace {

TEST(SlowTakesTest, ATakeLongerThanOneAndAHalfTimesTheOthersMedianIsSlow) {
  // The others' median is 160 samples: 241 is past 1.5 times it, 240 is not.
  std::vector<KeptTake> takes = {
      {"demo_0", 150}, {"demo_1", 160}, {"demo_2", 170}, {"demo_3", 241}};
  EXPECT_EQ(SlowTakes(takes), std::vector<size_t>{3});
  takes[3].samples = 240;
  EXPECT_TRUE(SlowTakes(takes).empty());
  EXPECT_EQ(SlowTakesWarning(takes, 0.1), "");
}

TEST(SlowTakesTest, TheWarningNamesEachSlowTakeWithItsSecondsAndTheOthers) {
  const std::vector<KeptTake> takes = {
      {"demo_0", 160}, {"demo_1", 400}, {"demo_2", 160}, {"demo_3", 500}};
  const std::string warning = SlowTakesWarning(takes, 0.1);
  EXPECT_NE(warning.find("Slow takes: demo_1 took 40.0 s"), std::string::npos) << warning;
  // demo_3's others: 160, 160 and 400 samples, median 16.0 s.
  EXPECT_NE(warning.find("demo_3 took 50.0 s, 3.1 times the others' 16.0 s"), std::string::npos)
      << warning;
  EXPECT_NE(warning.find("re-record them"), std::string::npos) << warning;
}

TEST(SlowTakesTest, OneTakeOrNoneHasNothingToCompareWith) {
  EXPECT_TRUE(SlowTakes({}).empty());
  EXPECT_TRUE(SlowTakes({{"demo_0", 6000}}).empty());
  EXPECT_EQ(SlowTakesWarning({{"demo_0", 6000}}, 0.1), "");
}

TEST(SlowTakesTest, ATenMinuteTakeAmongShortOnesIsPointedOut) {
  const std::string warning =
      SlowTakesWarning({{"demo_0", 180}, {"demo_1", 6000}, {"demo_2", 170}}, 0.1);
  EXPECT_NE(warning.find("A slow take: demo_1 took 600.0 s"), std::string::npos) << warning;
  EXPECT_NE(warning.find("re-record it"), std::string::npos) << warning;
}

}  // namespace
}  // namespace recon::teach
