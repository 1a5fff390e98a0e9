// `recon uwb monitor` on a pseudo-terminal with a fake DWM1001 behind it, as a user would run it
// on /dev/ttyACM0.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
  // Unplugged while streaming: the readings so far, the counts, then the error.
  uwb::FakeDwm1001 fake({[] { return std::string("POS,1.00,2.00,0.00,70\r\n"); }, 20});
  std::thread unplug([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    fake.Unplug();
  });
  r = testing::RunRecon("uwb monitor --port " + fake.port());
  unplug.join();
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("hung up"));
  EXPECT_THAT(r.output, HasSubstr("readings;"));
}

}  // namespace
}  // namespace recon
