// The DWM1001 driver on a real serial port: a pseudo-terminal whose other side answers as the
// PANS shell does (FakeDwm1001), streaming simulated or scripted `lec`/`lep` lines.

#include "devices/uwb/dwm1001_driver.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <fcntl.h>
#include <chrono>
#include <thread>

#include "devices/uwb/fake_dwm1001.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "engine/core/error.h"

namespace recon::uwb {
namespace {

using ::testing::HasSubstr;

/// Polls for `seconds`, collecting readings; stops early if the tag goes away.
std::vector<TimedReading> Collect(Dwm1001Driver& driver, double seconds) {
  std::vector<TimedReading> readings;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until && driver.Poll(readings, 20)) {
  }
  return readings;
}

TEST(Dwm1001DriverTest, EntersTheShellStartsTheStreamAndParsesSimulatedUpdates) {
  SimulatedDwm1001Options options;
  options.seed = 21;
  options.garble_probability = 0.2;  // plenty of interleaved echoes to resynchronise on
  SimulatedDwm1001 tag(options);
  const Eigen::Vector3d at(0.5, 0.3, 0.0);                     // table frame
  FakeDwm1001 fake({[&] { return tag.NextUpdate(at); }, 20});  // 50 Hz, to be quick
  Dwm1001Driver driver(fake.port());
  const std::vector<TimedReading> readings = Collect(driver, 1.5);
  EXPECT_TRUE(fake.streaming()) << "the driver typed lec";
  ASSERT_GE(readings.size(), 20u);
  // Garbled lines are dropped or resynchronised, never half-read; the position averages to where
  // the beacon is (in the anchor frame, which the default table_to_uwb leaves as the table's).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int with_position = 0;
  for (const TimedReading& r : readings) {
    if (!r.reading.has_position) continue;
    mean += Eigen::Vector3d(r.reading.x_m, r.reading.y_m, r.reading.z_m);
    ++with_position;
    EXPECT_EQ(r.reading.anchors.size(), 4u);
  }
  ASSERT_GT(with_position, 10);
  mean /= with_position;
  EXPECT_NEAR(mean.x(), options.table_to_uwb.Apply(at).x(), 0.05);
  EXPECT_NEAR(mean.y(), options.table_to_uwb.Apply(at).y(), 0.05);
  const ParseStats& stats = driver.stats();
  EXPECT_EQ(stats.lines, stats.readings + stats.malformed + stats.empty);
  EXPECT_GT(stats.malformed + stats.resynced, 0) << "20% garbled lines must show";
  for (size_t i = 1; i < readings.size(); ++i) EXPECT_GE(readings[i].t_s, readings[i - 1].t_s);
}

TEST(Dwm1001DriverTest, ScriptedLinesAndGarbageArriveAsTheyShould) {
  int update = 0;
  FakeDwm1001 fake({[&]() -> std::string {
                      switch (update++ % 3) {
                        case 0:
                          return "POS,1.20,0.80,0.10,95\r\n";
                        case 1:
                          return "#%&garbage,1,2\r\n";
                        default:
                          return "lePOS,1.30,0.70,0.20,90\r\n";  // an echo glued on
                      }
                    },
                    20});
  Dwm1001Driver driver(fake.port());
  const std::vector<TimedReading> readings = Collect(driver, 1.0);
  ASSERT_GE(readings.size(), 6u);
  bool clean = false, resynced = false;
  for (const TimedReading& r : readings) {
    ASSERT_TRUE(r.reading.has_position);
    clean |= r.reading.x_m == 1.20 && r.reading.quality == 95;
    resynced |= r.reading.x_m == 1.30 && r.reading.quality == 90;
  }
  EXPECT_TRUE(clean);
  EXPECT_TRUE(resynced);
  EXPECT_GE(driver.stats().malformed, 2);
  EXPECT_GE(driver.stats().resynced, 2);
}

TEST(Dwm1001DriverTest, AnUnpluggedTagIsReportedAndNeverCrashes) {
  FakeDwm1001 fake({[] { return std::string("POS,1.00,1.00,0.00,80\r\n"); }, 20});
  Dwm1001Driver driver(fake.port());
  EXPECT_FALSE(Collect(driver, 0.3).empty());
  fake.Unplug();
  std::vector<TimedReading> after;
  bool alive = true;
  for (int i = 0; i < 50 && alive; ++i) alive = driver.Poll(after, 20);
  EXPECT_FALSE(alive);
  EXPECT_FALSE(driver.connected());
  EXPECT_THAT(driver.last_error(), HasSubstr("hung up"));
  EXPECT_FALSE(driver.Poll(after, 20));  // and stays quiet
  // The port is gone with its master: reconnecting says so.
  EXPECT_THROW(driver.Reconnect(), UserError);
}

TEST(Dwm1001DriverTest, APortWithoutADwm1001OrWithoutADeviceIsNamed) {
  // A pseudo-terminal nobody answers on.
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  const std::string silent = ptsname(master);
  try {
    Dwm1001Driver driver(silent, 300);
    FAIL() << "a silent port was taken for a DWM1001";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no DWM1001 shell answered on " + silent + " within 300 ms"));
    EXPECT_THAT(e.what(), HasSubstr("115200"));
  }
  close(master);
  try {
    Dwm1001Driver driver("/dev/ttyACM-recon-missing");
    FAIL() << "a missing port was opened";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot open the serial port /dev/ttyACM-recon-missing"));
    EXPECT_THAT(e.what(), HasSubstr("plugged in"));
  }
}

}  // namespace
}  // namespace recon::uwb
