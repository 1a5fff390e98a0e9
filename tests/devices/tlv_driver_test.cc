// The DWM1001 in TLV mode on a real pseudo-terminal: the fake answers with the firmware's bytes,
// the driver polls loc_get, and both modes read the node id.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "devices/uwb/dwm1001_driver.h"
#include "devices/uwb/fake_dwm1001.h"
#include "devices/uwb/serial_port.h"
#include "devices/uwb/simulated_dwm1001.h"
#include "devices/uwb/tlv_codec.h"

namespace recon::uwb {
namespace {

/// Reads from `port` until `frames` holds `count` frames or a second passes.
std::vector<TlvFrame> Exchange(SerialPort& port, const std::string& request, size_t count) {
  TlvResponseParser parser;
  std::vector<TlvFrame> frames;
  EXPECT_TRUE(port.Write(request));
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (frames.size() < count && std::chrono::steady_clock::now() < until) {
    std::string bytes;
    if (!port.Read(bytes, 20)) break;
    parser.Feed(bytes, frames);
  }
  EXPECT_EQ(parser.stats().dropped_bytes, 0) << static_cast<int>(request[0]);
  return frames;
}

UwbReading Scripted() {
  UwbReading r;
  r.has_position = true;
  r.x_m = 0.61;
  r.y_m = 0.47;
  r.z_m = 0.05;
  r.quality = 88;
  r.anchors = {{0x0C8A, 0.0, 0.0, 1.2, 1.5}, {0x1D42, 2.4, 0.0, 1.2, 2.25}};
  return r;
}

TEST(TlvDriverTest, TheFakeAnswersTlvRequestsWithTheFirmwaresBytes) {
  FakeDwm1001::Options options;
  options.next_reading = Scripted;
  options.period_ms = 20;
  options.node_id = 0xDECA0000000012ABull;
  FakeDwm1001 fake(options);
  SerialPort port(fake.port());
  std::this_thread::sleep_for(std::chrono::milliseconds(60));  // one update has happened

  std::vector<TlvFrame> f = Exchange(port, EncodeLocGet(), 3);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].error, 0);
  EXPECT_DOUBLE_EQ(f[1].reading.x_m, 0.61);
  EXPECT_EQ(f[1].reading.quality, 88);
  EXPECT_EQ(f[2].reading.anchors, Scripted().anchors);

  f = Exchange(port, EncodeNodeIdGet(), 2);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[1].node_id, 0xDECA0000000012ABull);

  f = Exchange(port, EncodeUpdRateSet(3, 10), 1);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].error, 0);
  EXPECT_EQ(fake.period_ms(), 300);
  EXPECT_EQ(
      Exchange(port, EncodeUpdRateSet(1, 1).substr(0, 2) + std::string(4, '\0'), 1).at(0).error,
      tlv::kInvalidParameter);

  f = Exchange(port, std::string{0x7E, 0x00}, 1);  // unknown type
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].error, tlv::kUnknownTlv);
  f = Exchange(port, std::string{0x02}, 1);  // a stray byte: the request never completes
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].error, tlv::kUnknownTlv);

  // The shell and back.
  ASSERT_TRUE(port.Write("\r\r"));
  std::string text;
  for (int i = 0; i < 50 && text.find("dwm>") == std::string::npos; ++i) port.Read(text, 20);
  EXPECT_TRUE(fake.in_shell());
  text.clear();
  ASSERT_TRUE(port.Write("si\r"));
  for (int i = 0; i < 50 && text.find("dwm>") == std::string::npos; ++i) port.Read(text, 20);
  EXPECT_THAT(text, ::testing::HasSubstr("addr=xDECA0000000012AB"));
  ASSERT_TRUE(port.Write("quit\r"));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  port.Read(text, 20);  // the echo of quit
  EXPECT_FALSE(fake.in_shell());
  f = Exchange(port, EncodePosGet(), 2);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[1].kind, TlvFrame::Kind::kPosition);
}

TEST(TlvDriverTest, PollsLocGetAtTheRateItSetAndReadsTheNodeId) {
  SimulatedDwm1001Options sim;
  sim.seed = 33;
  SimulatedDwm1001 tag(sim);
  const Eigen::Vector3d at(0.8, 0.4, 0.0);
  FakeDwm1001::Options options;
  options.next_reading = [&] { return tag.NextReading(at); };
  options.period_ms = 20;
  options.node_id = 0x00000000000ABCDEull;
  FakeDwm1001 fake(options);
  Dwm1001Driver driver(fake.port(),
                       Dwm1001Options{.mode = Dwm1001Mode::kTlvPolling, .update_period_ms = 100});
  EXPECT_EQ(driver.node_id(), 0xABCDEull);
  EXPECT_EQ(fake.period_ms(), 100) << "upd_rate_set reached the tag";
  EXPECT_FALSE(fake.in_shell());
  std::vector<TimedReading> readings;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1200);
  while (std::chrono::steady_clock::now() < until) ASSERT_TRUE(driver.Poll(readings, 20));
  ASSERT_GE(readings.size(), 5u);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int with_position = 0;
  for (const TimedReading& r : readings) {
    if (!r.reading.has_position) continue;  // a poll before the first update
    EXPECT_EQ(r.reading.anchors.size(), 4u);
    mean += Eigen::Vector3d(r.reading.x_m, r.reading.y_m, r.reading.z_m);
    ++with_position;
  }
  ASSERT_GE(with_position, 4);
  mean /= with_position;
  EXPECT_NEAR(mean.x(), 0.8, 0.1);
  EXPECT_NEAR(mean.y(), 0.4, 0.1);
  const Dwm1001Counts counts = driver.counts();
  EXPECT_EQ(counts.readings, static_cast<int64_t>(readings.size()));
  EXPECT_EQ(counts.malformed, 0);
  EXPECT_EQ(driver.tlv_stats().dropped_bytes, 0);
}

TEST(TlvDriverTest, TheShellModeReadsTheNodeIdWithSiAndStreamsStructuredUpdates) {
  FakeDwm1001::Options options;
  options.next_reading = Scripted;
  options.period_ms = 20;
  options.node_id = 0xDECA0000000012ABull;
  FakeDwm1001 fake(options);
  Dwm1001Driver driver(fake.port());
  EXPECT_EQ(driver.node_id(), 0xDECA0000000012ABull);
  EXPECT_EQ(NodeIdHex(driver.node_id()), "DECA0000000012AB");
  std::vector<TimedReading> readings;
  for (int i = 0; i < 50 && readings.size() < 3; ++i) ASSERT_TRUE(driver.Poll(readings, 20));
  ASSERT_GE(readings.size(), 3u);
  EXPECT_EQ(readings[0].reading, Scripted());
  EXPECT_EQ(driver.stats().malformed, 0) << "the si output never reaches the lec parser";
}

TEST(TlvDriverTest, ATlvDriverFindsATagLeftInTheShell) {
  FakeDwm1001::Options options;
  options.next_reading = Scripted;
  options.period_ms = 20;
  options.node_id = 42;
  FakeDwm1001 fake(options);
  { Dwm1001Driver shell(fake.port()); }  // leaves the tag in the shell
  EXPECT_TRUE(fake.in_shell());
  Dwm1001Driver driver(fake.port(), Dwm1001Options{.mode = Dwm1001Mode::kTlvPolling});
  EXPECT_EQ(driver.node_id(), 42u);
  EXPECT_FALSE(fake.in_shell());
}

}  // namespace
}  // namespace recon::uwb
