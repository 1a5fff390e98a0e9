// Several DWM1001 tags on real pseudo-terminals behind one BeaconHub: told apart by node id,
// unplugged and plugged back in (through a udev-like symlink), never stopping the others.

#include "devices/uwb/beacon_hub.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "devices/uwb/fake_dwm1001.h"
#include "engine/core/error.h"

namespace recon::uwb {
namespace {

using ::testing::HasSubstr;

/// A tag that always reports `x_m` (so its readings are told apart by value too).
std::unique_ptr<FakeDwm1001> Tag(uint64_t node_id, double x_m) {
  FakeDwm1001::Options options;
  options.period_ms = 20;
  options.node_id = node_id;
  options.next_reading = [x_m] {
    UwbReading r;
    r.has_position = true;
    r.x_m = x_m;
    r.y_m = 0.5;
    r.quality = 90;
    r.anchors = {{0x0C8A, 0.0, 0.0, 1.2, 1.0}};
    return r;
  };
  return std::make_unique<FakeDwm1001>(options);
}

/// Readings per beacon name over `seconds`.
std::map<std::string, std::vector<BeaconReading>> Collect(BeaconHub& hub, double seconds) {
  std::map<std::string, std::vector<BeaconReading>> by_name;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    for (BeaconReading& r : hub.PollReadings(20)) by_name[r.beacon].push_back(std::move(r));
  }
  return by_name;
}

/// A temporary directory, removed at the end of the test.
struct TempDir {
  TempDir() {
    char pattern[] = "/tmp/recon-beacon-hub-XXXXXX";
    path = ::mkdtemp(pattern);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::filesystem::path path;
};

constexpr uint64_t kPlateId = 0xDECA0000000000A1ull;
constexpr uint64_t kOtherId = 0xDECA0000000000B2ull;

TEST(BeaconHubTest, TwoTagsAreToldApartAndAnUnplugStopsOnlyOne) {
  auto plate = Tag(kPlateId, 0.25);
  auto other = Tag(kOtherId, 1.75);
  BeaconHubOptions options;
  options.ports = {plate->port(), other->port()};
  options.names = {{"0xdeca0000000000a1", "plate"}};
  options.driver.mode = Dwm1001Mode::kTlvPolling;
  BeaconHub hub(options);
  ASSERT_EQ(hub.connected_count(), 2) << hub.Describe();

  auto by_name = Collect(hub, 1.0);
  ASSERT_EQ(by_name.size(), 2u);
  ASSERT_GE(by_name["plate"].size(), 4u);
  ASSERT_GE(by_name["DECA0000000000B2"].size(), 4u) << "an unmapped id is named by its hex";
  for (const BeaconReading& r : by_name["plate"]) {
    EXPECT_EQ(r.port, plate->port());
    EXPECT_EQ(r.node_id, kPlateId);
    if (r.reading.has_position) {
      EXPECT_DOUBLE_EQ(r.reading.x_m, 0.25);
    }
  }
  for (const BeaconReading& r : by_name["DECA0000000000B2"]) {
    if (r.reading.has_position) {
      EXPECT_DOUBLE_EQ(r.reading.x_m, 1.75);
    }
  }

  other->Unplug();
  by_name = Collect(hub, 1.0);
  EXPECT_GE(by_name["plate"].size(), 4u) << "the plate keeps streaming";
  const std::vector<BeaconPortStatus> status = hub.Status();
  ASSERT_EQ(status.size(), 2u);
  EXPECT_TRUE(status[0].connected);
  EXPECT_EQ(status[0].beacon, "plate");
  EXPECT_GT(status[0].readings, 8);
  EXPECT_FALSE(status[1].connected);
  EXPECT_EQ(status[1].node_id, kOtherId);
  EXPECT_THAT(status[1].last_error, HasSubstr(other->port()));
  EXPECT_THAT(hub.Describe(), HasSubstr("reconnecting"));
  // The BeaconSource view: samples with names, positions in metres, nothing thrown.
  std::vector<devices::BeaconSample> samples;
  for (int i = 0; i < 50 && samples.empty(); ++i) {
    samples = hub.Poll();
    usleep(10000);
  }
  ASSERT_FALSE(samples.empty());
  EXPECT_EQ(samples[0].beacon, "plate");
  EXPECT_DOUBLE_EQ(samples[0].position_uwb_m.x(), 0.25);
  const std::vector<BeaconPortStatus> now = hub.Status();
  EXPECT_EQ(hub.Stats().readings, now[0].readings + now[1].readings);
}

TEST(BeaconHubTest, AReplugBehindAStableSymlinkIsReconnectedWithinASecondOrTwo) {
  TempDir dir;
  const std::filesystem::path link = dir.path / "usb-SEGGER_J-Link_000760000001-if00";
  auto first = Tag(kPlateId, 0.25);
  std::filesystem::create_symlink(first->port(), link);
  BeaconHubOptions options;
  options.ports = {link.string()};
  options.names = {{"DECA0000000000A1", "plate"}};
  BeaconHub hub(options);  // lec mode
  EXPECT_FALSE(Collect(hub, 0.5)["plate"].empty());

  first->Unplug();
  auto by_name = Collect(hub, 0.3);
  EXPECT_FALSE(hub.Status()[0].connected);
  // The tag comes back, as udev would bring it: a new device node behind the same link.
  auto second = Tag(kPlateId, 0.30);
  const std::filesystem::path fresh = dir.path / "new-link";
  std::filesystem::create_symlink(second->port(), fresh);
  std::filesystem::rename(fresh, link);
  by_name = Collect(hub, 2.5);
  const BeaconPortStatus status = hub.Status()[0];
  EXPECT_TRUE(status.connected) << status.last_error;
  EXPECT_EQ(status.reconnects, 1);
  bool from_second = false;
  for (const BeaconReading& r : by_name["plate"]) from_second |= r.reading.x_m == 0.30;
  EXPECT_TRUE(from_second);
}

TEST(BeaconHubTest, AMissingPortAtStartIsRetriedNotThrown) {
  auto plate = Tag(kPlateId, 0.25);
  BeaconHubOptions options;
  options.ports = {"/dev/ttyACM-recon-missing", plate->port()};
  options.retry_period_s = 0.2;
  BeaconHub hub(options);
  EXPECT_EQ(hub.connected_count(), 1);
  auto by_name = Collect(hub, 0.7);
  EXPECT_FALSE(by_name["DECA0000000000A1"].empty());
  const BeaconPortStatus missing = hub.Status()[0];
  EXPECT_FALSE(missing.connected);
  EXPECT_THAT(missing.last_error,
              HasSubstr("cannot open the serial port /dev/ttyACM-recon-missing"));
  EXPECT_EQ(missing.reconnects, 0);
}

TEST(BeaconHubTest, OptionsThatCanNeverWorkAreUserErrors) {
  EXPECT_THROW(BeaconHub(BeaconHubOptions{}), UserError);
  BeaconHubOptions twice;
  twice.ports = {"/dev/ttyACM-x", "/dev/ttyACM-x"};
  EXPECT_THROW(BeaconHub{twice}, UserError);
  BeaconHubOptions bad_key;
  bad_key.ports = {"/dev/ttyACM-x"};
  bad_key.names = {{"plate", "DECA0000000000A1"}};  // swapped
  try {
    BeaconHub hub(bad_key);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("\"plate\""));
  }
}

}  // namespace
}  // namespace recon::uwb
