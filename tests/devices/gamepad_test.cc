// The gamepad driver through a real file descriptor: a FIFO carrying the Linux joystick API's
// 8-byte events, written in pieces as a device's would arrive, and the stick mapping.

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <linux/joystick.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "devices/teleop/gamepad_mapping.h"
#include "devices/teleop/linux_joystick.h"
#include "engine/core/error.h"

namespace recon::teleop {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::vector<unsigned char> Event(uint32_t time, int16_t value, uint8_t type, uint8_t number) {
  js_event e{time, value, type, number};
  std::vector<unsigned char> bytes(sizeof(e));
  std::memcpy(bytes.data(), &e, sizeof(e));
  return bytes;
}

class GamepadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("recon-gamepad-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fifo_ = (dir_ / "js0").string();
    ASSERT_EQ(mkfifo(fifo_.c_str(), 0600), 0);
  }
  void TearDown() override {
    if (writer_ >= 0) close(writer_);
    fs::remove_all(dir_);
  }
  void Write(const std::vector<unsigned char>& bytes) {
    ASSERT_EQ(write(writer_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
  fs::path dir_;
  std::string fifo_;
  int writer_ = -1;
};

TEST_F(GamepadTest, ReadsAxesAndButtonsIncludingEventsSplitAcrossReads) {
  LinuxJoystick pad(fifo_);  // the reader opens first (non-blocking), then the "device" writes
  writer_ = open(fifo_.c_str(), O_WRONLY);
  ASSERT_GE(writer_, 0);
  EXPECT_EQ(pad.name(), "gamepad");  // a FIFO has no JSIOCGNAME
  EXPECT_TRUE(pad.Poll());           // nothing yet
  EXPECT_TRUE(pad.state().axes.empty());
  // The initial state, as the driver sends it on open, then a stick pushed right.
  Write(Event(10, 0, JS_EVENT_AXIS | JS_EVENT_INIT, 0));
  Write(Event(10, 0, JS_EVENT_BUTTON | JS_EVENT_INIT, 0));
  const std::vector<unsigned char> right = Event(20, 32767, JS_EVENT_AXIS, 0);
  Write({right.begin(), right.begin() + 3});  // half an event...
  EXPECT_TRUE(pad.Poll());
  EXPECT_EQ(pad.state().axes.at(0), 0.0f);
  Write({right.begin() + 3, right.end()});  // ...and the rest
  Write(Event(30, 1, JS_EVENT_BUTTON, 7));
  Write(Event(31, -16384, JS_EVENT_AXIS, 4));
  Write(Event(32, 5, 0x7f, 200));  // garbage: ignored, counted
  EXPECT_TRUE(pad.Poll());
  EXPECT_FLOAT_EQ(pad.state().axes.at(0), 1.0f);
  EXPECT_NEAR(pad.state().axes.at(4), -0.5f, 1e-4);
  EXPECT_TRUE(pad.state().buttons.at(7));
  EXPECT_EQ(pad.state().time_ms, 32u);
  EXPECT_EQ(pad.events(), 6u);
  // Unplugged: reported, not thrown.
  close(writer_);
  writer_ = -1;
  EXPECT_FALSE(pad.Poll());
  EXPECT_FALSE(pad.connected());
  EXPECT_THAT(pad.last_error(), HasSubstr("js0 closed"));
  EXPECT_FALSE(pad.Poll());
}

TEST_F(GamepadTest, MissingDevicesAreNamedAndFoundByName) {
  try {
    LinuxJoystick pad((dir_ / "js9").string());
    FAIL() << "opened a device that does not exist";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot open the gamepad"));
    EXPECT_THAT(e.what(), HasSubstr("js9"));
  }
  for (const char* name : {"js12", "jsx", "event3", "js"}) std::ofstream(dir_ / name) << "";
  EXPECT_EQ(LinuxJoystick::Find(dir_.string()),
            (std::vector<std::string>{(dir_ / "js0").string(), (dir_ / "js12").string()}));
  EXPECT_TRUE(LinuxJoystick::Find((dir_ / "nowhere").string()).empty());
}

TEST(GamepadMapping, DeadZoneInvertedYAndButtonEdges) {
  EXPECT_EQ(DeadZone(0.1f), 0.0f);
  EXPECT_EQ(DeadZone(-0.15f), 0.0f);
  EXPECT_FLOAT_EQ(DeadZone(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(DeadZone(-1.0f), -1.0f);
  EXPECT_NEAR(DeadZone(0.575f), 0.5f, 1e-6);
  EXPECT_EQ(DeadZone(NAN), 0.0f);
  GamepadState before, now;
  now.axes = {0.05f, -1.0f, 0.0f, 0.0f, 1.0f};
  now.buttons = {true, false, false, false, false, false, false, true};
  GamepadTeleop t = MapGamepad(now, before);
  EXPECT_EQ(t.screen_right, 0.0f);     // inside the dead zone
  EXPECT_FLOAT_EQ(t.screen_up, 1.0f);  // stick pushed away (y = -1) moves up the screen
  EXPECT_FLOAT_EQ(t.raise, -1.0f);     // right stick pulled back lowers the tool
  EXPECT_TRUE(t.toggle_gripper);
  EXPECT_TRUE(t.keep);
  t = MapGamepad(now, now);  // held, not pressed again
  EXPECT_FALSE(t.toggle_gripper);
  EXPECT_FALSE(t.keep);
}

}  // namespace
}  // namespace recon::teleop
