// The warning a teacher gets when their demonstrations mix teleops.

#include "engine/teach/teacher_mix.h"

#include <gtest/gtest.h>

namespace recon::teach {
namespace {

TEST(TeacherMixTest, OneTeacherSaysNothingTwoAreNamedAndCounted) {
  EXPECT_EQ(TeacherMixWarning({}), "");
  EXPECT_EQ(TeacherMixWarning({"keyboard-teleop", "keyboard-teleop"}), "");
  const std::string mixed = TeacherMixWarning(
      {"scripted-teleop", "keyboard-teleop", "scripted-teleop", "scripted-teleop", "x-device"});
  EXPECT_NE(mixed.find("3 teachers"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("3 by the scripted teacher"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("1 by the keyboard"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("1 by x-device"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("Bad"), std::string::npos) << "it says what to do";
}

TEST(TeacherMixTest, EveryTeleopButTheScriptedTeachersIsAPerson) {
  EXPECT_FALSE(IsAPersonsTake("scripted-teleop"));
  for (const char* source : {"keyboard-teleop", "gamepad-teleop", "real-teleop", ""}) {
    EXPECT_TRUE(IsAPersonsTake(source)) << source;
  }
}

TEST(TeacherMixTest, MostTakesByAPersonMeansMoreThanHalf) {
  EXPECT_TRUE(MostlyAPersonsTakes({true, true, false}));
  EXPECT_FALSE(MostlyAPersonsTakes({true, false}));
  EXPECT_FALSE(MostlyAPersonsTakes({false, false, true}));
  EXPECT_FALSE(MostlyAPersonsTakes({}));
}

}  // namespace
}  // namespace recon::teach
