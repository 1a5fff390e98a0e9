// `recon uwb monitor` on a pseudo-terminal with a fake DWM1001 behind it, as a user would run it
// on /dev/ttyACM0.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "devices/uwb/fake_dwm1001.h"
#include "tests/app/run_recon.h"

namespace recon {
namespace {

using ::testing::HasSubstr;

TEST(UwbCliTest, MonitorPrintsOneJsonReadingPerLineAndTheDroppedCount) {
  int update = 0;
  uwb::FakeDwm1001 fake({[&]() -> std::string {
                           return update++ % 2 == 0 ? "POS,0.61,0.47,0.05,88\r\n"
                                                    : "POS,0.6#,garbled\r\n";
                         },
                         20});
  const testing::CommandResult r =
      testing::RunRecon("uwb monitor --port " + fake.port() + " --count 5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::istringstream lines(r.output);
  std::string line;
  int readings = 0;
  nlohmann::json last;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] != '{') continue;
    last = nlohmann::json::parse(line);
    if (last.contains("x")) {
      ++readings;
      EXPECT_DOUBLE_EQ(last["x"].get<double>(), 0.61);
      EXPECT_DOUBLE_EQ(last["y"].get<double>(), 0.47);
      EXPECT_DOUBLE_EQ(last["z"].get<double>(), 0.05);
      EXPECT_EQ(last["qf"].get<int>(), 88);
      EXPECT_TRUE(last.contains("t"));
    }
  }
  EXPECT_EQ(readings, 5);
  ASSERT_TRUE(last.contains("dropped_lines")) << r.output;
  EXPECT_GE(last["dropped_lines"].get<int>(), 4);
  EXPECT_EQ(last["readings"].get<int>(), 5);
}

TEST(UwbCliTest, AMissingPortOrAnUnpluggedTagIsAClearError) {
  testing::CommandResult r = testing::RunRecon("uwb monitor --port /dev/ttyACM-recon-missing");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("cannot open the serial port /dev/ttyACM-recon-missing"));
  r = testing::RunRecon("uwb monitor");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--port"));
  r = testing::RunRecon("uwb monitor --fake 1 --mode binary");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--mode"));
  r = testing::RunRecon("uwb monitor --fake 1 --name plate --count 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("NODE_ID=NAME"));
  // Unplugged while streaming: the readings so far, the counts, then the error.
  uwb::FakeDwm1001 fake({[] { return std::string("POS,1.00,2.00,0.00,70\r\n"); }, 20});
  // Unplugged once the monitor has been streaming for a while (5 updates), not after a fixed
  // time: under load the monitor took longer than 1.5 s to open the port, and then only the open
  // failed. The deadline only bounds a monitor that never starts.
  std::thread unplug([&] {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (fake.updates_sent() < 5 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    fake.Unplug();
  });
  r = testing::RunRecon("uwb monitor --port " + fake.port());
  unplug.join();
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("hung up"));
  EXPECT_THAT(r.output, HasSubstr("readings;"));
}

uwb::UwbReading At(double x_m) {
  uwb::UwbReading r;
  r.has_position = true;
  r.x_m = x_m;
  r.y_m = 0.5;
  r.quality = 77;
  r.anchors = {{0x0C8A, 0.0, 0.0, 1.2, 1.25}};
  return r;
}

TEST(UwbCliTest, MonitorPollsTwoTagsInTlvModeAndTellsThemApart) {
  uwb::FakeDwm1001::Options a;
  a.period_ms = 20;
  a.node_id = 0xDECA0000000000A1ull;
  a.next_reading = [] { return At(0.25); };
  uwb::FakeDwm1001::Options b = a;
  b.node_id = 0xDECA0000000000B2ull;
  b.next_reading = [] { return At(1.75); };
  uwb::FakeDwm1001 plate(a), cup(b);
  const testing::CommandResult r =
      testing::RunRecon("uwb monitor --mode tlv --port " + plate.port() + " --port " + cup.port() +
                        " --name DECA0000000000A1=plate --seconds 1.2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(plate.tlv_requests(), 5) << "the monitor polled in TLV mode";
  EXPECT_FALSE(plate.in_shell());
  std::istringstream lines(r.output);
  std::string line;
  std::map<std::string, int> readings;
  std::map<std::string, nlohmann::json> counts;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] != '{') continue;
    const nlohmann::json j = nlohmann::json::parse(line);
    if (j.contains("responses")) {
      counts[j["port"].get<std::string>()] = j;
      continue;
    }
    if (!j.contains("x")) continue;
    const std::string id = j["id"].get<std::string>();
    ++readings[id];
    EXPECT_TRUE(j.contains("t") && j.contains("qf") && j.contains("anchors")) << line;
    if (id == "DECA0000000000A1") {
      EXPECT_EQ(j["port"].get<std::string>(), plate.port());
      EXPECT_EQ(j["beacon"].get<std::string>(), "plate");
      EXPECT_DOUBLE_EQ(j["x"].get<double>(), 0.25);
    } else {
      EXPECT_EQ(id, "DECA0000000000B2");
      EXPECT_EQ(j["port"].get<std::string>(), cup.port());
      EXPECT_DOUBLE_EQ(j["x"].get<double>(), 1.75);
    }
  }
  EXPECT_GE(readings["DECA0000000000A1"], 4);
  EXPECT_GE(readings["DECA0000000000B2"], 4);
  ASSERT_EQ(counts.size(), 2u) << r.output;
  EXPECT_EQ(counts[plate.port()]["id"], "DECA0000000000A1");
  EXPECT_GE(counts[cup.port()]["readings"].get<int>(), 4);
  EXPECT_EQ(counts[cup.port()]["malformed_responses"].get<int>(), 0);
}

TEST(UwbCliTest, MonitorRunsAgainstBuiltInFakeTags) {
  const testing::CommandResult r = testing::RunRecon("uwb monitor --fake 2 --count 6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("DECA00000000F001"));
  EXPECT_THAT(r.output, HasSubstr("readings;"));
}

}  // namespace
}  // namespace recon
