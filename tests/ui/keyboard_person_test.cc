// The scripted person's eyes and hands on synthetic screens: what it sees in the 3-D view and on
// the readout, and which keys it answers with. (StudioPersonTest runs it in the whole studio.)

#include "ui/testing/keyboard_person.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/testing/colour_blob.h"

namespace recon::ui {
namespace {

bool Holds(const FrameInput& keys, ImGuiKey key) {
  return std::count(keys.keys_down.begin(), keys.keys_down.end(), key) > 0;
}
bool Presses(const FrameInput& keys, ImGuiKey key) {
  return std::count(keys.keys_pressed.begin(), keys.keys_pressed.end(), key) > 0;
}

// A 200 x 150 view: a grey table, the toast (a crust-coloured patch, its middle at (100, 70))
// and the blue plate (a disc around (160, 40)).
RgbImage SyntheticView(bool with_plate = true) {
  RgbImage image;
  image.width = 200;
  image.height = 150;
  image.rgb.resize(200 * 150 * 3);
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) {
      uint8_t* p = image.rgb.data() + (y * 200 + x) * 3;
      p[0] = 219, p[1] = 214, p[2] = 199;  // the table
      if (x >= 80 && x < 120 && y >= 60 && y < 84) p[0] = 217, p[1] = 158, p[2] = 77;
      if (with_plate && std::hypot(x - 160, y - 40) < 15) p[0] = 38, p[1] = 77, p[2] = 217;
    }
  }
  return image;
}

StudioSnapshot Screen(float spot_x, float spot_y, float height) {
  StudioSnapshot s;
  s.recording = true;
  s.teleop = TeleopMode::kKeyboard;
  s.teacher_view.available = true;
  s.teacher_view.image = SyntheticView();
  s.teacher_view.spot_pixel = {spot_x, spot_y};
  s.grip_m = {0.3f, 0.0f, height};
  s.grip = {GripState::kOpen, "toast", 0.005f, 0.011f};
  return s;
}

TEST(ColourBlobTest, TheLargestPatchOfAColourIsFoundWithItsCentreAndBounds) {
  const auto blob = LargestBlob(SyntheticView(), [](int r, int g, int b) { return b > 2 * r; });
  ASSERT_TRUE(blob.has_value());
  EXPECT_NEAR(blob->centre_x, 160, 0.5);
  EXPECT_NEAR(blob->centre_y, 40, 0.5);
  EXPECT_EQ(blob->left, 146);
  EXPECT_EQ(blob->right, 174);
  EXPECT_FALSE(LargestBlob(SyntheticView(), [](int, int g, int) { return g > 250; }));
}

TEST(KeyboardPersonTest, ItWaitsForTheCountdownThenSteersTheSpotOntoTheToast) {
  KeyboardPerson person;
  StudioSnapshot s = Screen(40, 70, 0.30f);
  s.countdown_s = 1.5;
  EXPECT_TRUE(person.Next(s).keys_down.empty()) << "the arm does not listen yet";
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kWaiting);
  s.countdown_s = 0;
  person.Next(s);  // looks
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kToToast);
  FrameInput keys = person.Next(s);
  EXPECT_TRUE(Holds(keys, ImGuiKey_RightArrow)) << "the toast is to the spot's right";
  EXPECT_FALSE(Holds(keys, ImGuiKey_LeftArrow));
  EXPECT_TRUE(Holds(keys, ImGuiKey_PageDown)) << "high above: down while lining up";
  // Below it and to the left: up and right. (The toast's top face is aimed at, a little above
  // the patch's middle: its near side shows under it.)
  keys = person.Next(Screen(60, 110, 0.30f));
  EXPECT_TRUE(Holds(keys, ImGuiKey_UpArrow));
  EXPECT_TRUE(Holds(keys, ImGuiKey_RightArrow));
  // Close above the grasp band but not yet lined up: no lower.
  keys = person.Next(Screen(60, 70, 0.03f));
  EXPECT_FALSE(Holds(keys, ImGuiKey_PageDown));
}

// A person moves the spot to the toast's middle, not to the first place near enough: the key
// stays down inside the tolerance until the middle, and a spot near enough is left alone until
// it drifts out again. (Stopping at the tolerance's edge put every grasp of the ideal person
// 7 mm short of the middle on the side it came from.)
TEST(KeyboardPersonTest, AHeldKeyTakesTheSpotToTheMiddleNotToTheEdgeOfNearEnough) {
  KeyboardPerson person;
  // The toast's middle as the person aims at it: x 99.5 (tolerance 7 % of 40 px: 2.8 px), y at
  // its top face (60 + 0.42 x 23).
  const float middle_x = 99.5f, middle_y = 60 + 0.42f * 23;
  StudioSnapshot s = Screen(40, middle_y, 0.30f);
  person.Next(s);  // looks
  EXPECT_TRUE(Holds(person.Next(s), ImGuiKey_RightArrow));
  EXPECT_TRUE(Holds(person.Next(Screen(middle_x - 2.0f, middle_y, 0.30f)), ImGuiKey_RightArrow))
      << "near enough, but not yet the middle";
  EXPECT_FALSE(Holds(person.Next(Screen(middle_x - 0.5f, middle_y, 0.30f)), ImGuiKey_RightArrow))
      << "at the middle";
  EXPECT_FALSE(Holds(person.Next(Screen(middle_x - 2.0f, middle_y, 0.30f)), ImGuiKey_RightArrow))
      << "drifted, but still near enough";
  EXPECT_TRUE(Holds(person.Next(Screen(middle_x - 4.0f, middle_y, 0.30f)), ImGuiKey_RightArrow))
      << "out of near enough again";
  // Past the middle on the way: let go there.
  EXPECT_FALSE(Holds(person.Next(Screen(middle_x + 0.8f, middle_y, 0.30f)), ImGuiKey_RightArrow));
  EXPECT_FALSE(Holds(person.Next(Screen(middle_x + 0.8f, middle_y, 0.30f)), ImGuiKey_LeftArrow));
}

TEST(KeyboardPersonTest, ItClosesInTheGraspBandAndRetriesAMiss) {
  KeyboardPerson person;
  StudioSnapshot s = Screen(100, 70, 0.02f);
  person.Next(s);  // looks
  // Low over the toast, it goes down only once the spot has stayed on it for three new views.
  for (uint64_t frame = 1; frame <= 3; ++frame) {
    s.teacher_view.frame = frame;
    EXPECT_EQ(Holds(person.Next(s), ImGuiKey_PageDown), frame == 3) << "view " << frame;
  }
  s.grip_m[2] = 0.009f;
  s.teacher_view.frame = 4;
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kGrasp);
  EXPECT_TRUE(Presses(person.Next(s), ImGuiKey_Space));
  EXPECT_EQ(person.grasp_attempts(), 1);
  // Closed on nothing: open again, rise, line up again.
  s.grip.state = GripState::kClosedOnNothing;
  s.gripper_closed = true;
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kReopen);
  EXPECT_TRUE(Presses(person.Next(s), ImGuiKey_Space));
  s.grip.state = GripState::kOpen;
  s.gripper_closed = false;
  EXPECT_TRUE(Holds(person.Next(s), ImGuiKey_PageUp));
  s.grip_m[2] = 0.05f;
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kToToast);
}

TEST(KeyboardPersonTest, HoldingTheToastItLiftsItAndCarriesItToThePlate) {
  KeyboardPerson person;
  StudioSnapshot s = Screen(100, 70, 0.009f);
  person.Next(s);
  for (uint64_t frame = 1; frame <= 4; ++frame) {
    s.teacher_view.frame = frame;
    person.Next(s);
  }
  ASSERT_EQ(person.phase(), KeyboardPerson::Phase::kGrasp);
  person.Next(s);  // Space
  s.grip.state = GripState::kHolding;
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kLift);
  EXPECT_TRUE(Holds(person.Next(s), ImGuiKey_PageUp));
  s.grip_m[2] = 0.13f;
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kToPlate);
  const FrameInput keys = person.Next(s);
  EXPECT_TRUE(Holds(keys, ImGuiKey_RightArrow)) << "the plate is up and to the right";
  EXPECT_TRUE(Holds(keys, ImGuiKey_UpArrow));
  // The take ended (the studio kept it): finished.
  s.recording = false;
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kFinished);
}

TEST(KeyboardPersonTest, WithoutThePlateInSightItSaysSo) {
  KeyboardPerson person;
  StudioSnapshot s = Screen(100, 70, 0.3f);
  s.teacher_view.image = SyntheticView(false);
  person.Next(s);
  EXPECT_EQ(person.phase(), KeyboardPerson::Phase::kLost);
  EXPECT_NE(person.Describe().find("no plate"), std::string::npos) << person.Describe();
}

}  // namespace
}  // namespace recon::ui
