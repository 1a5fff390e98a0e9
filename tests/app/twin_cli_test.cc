// `recon twin`: a digital twin a user starts from the command line and opens as a real cell. The
// test runs `recon twin up` as its own process, opens its profile as the studio would (the camera
// located from the rendered table tags, the beacon read over its pseudo-terminal), moves the
// plate with `recon twin move` and sees the beacon follow through the hidden UWB frame, and
// stops it with SIGTERM.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "devices/cell/cell_profile.h"
#include "devices/cell/real_cell.h"
#include "devices/cell/twin_scene.h"
#include "tests/app/run_recon.h"
#include "tests/app/spawn_recon.h"

namespace recon::cell {
namespace {

namespace fs = std::filesystem;
using recon::testing::CommandResult;
using recon::testing::RunRecon;
using ::testing::HasSubstr;

/// The mean of the plate beacon's readings over `seconds` (the twin adds +-2 cm of noise).
std::optional<Eigen::Vector3d> MeanReading(RealCell& cell, double seconds) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    for (const devices::BeaconSample& s : cell.beacons().Poll()) {
      if (s.beacon != "plate") continue;
      sum += s.position_uwb_m;
      ++n;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (n == 0) return std::nullopt;
  return sum / n;
}

TEST(TwinCliTest, ATwinStartedFromTheCommandLineIsARealCellWhoseObjectsMove) {
  char pattern[] = "/tmp/recon-twin-cli-XXXXXX";
  ASSERT_NE(::mkdtemp(pattern), nullptr);
  const fs::path dir = pattern;
  const pid_t twin = recon::testing::SpawnRecon(
      {"twin", "up", (dir / "twin").string(), "--seed", "7", "--seconds", "120"});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!fs::exists(dir / "twin" / "cell.json") && std::chrono::steady_clock::now() < deadline &&
         !recon::testing::HasEnded(twin)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(fs::exists(dir / "twin" / "cell.json")) << "recon twin up wrote no profile";
  {
    RealCell cell(ReadCellProfile((dir / "twin" / "cell.json").string()));
    ASSERT_TRUE(cell.camera_pose().has_value()) << cell.camera_pose_error();
    EXPECT_LT(cell.camera_pose()->reprojection_rms_px, 1.0);
    ASSERT_NE(cell.arm(), nullptr);
    const std::optional<Eigen::Vector3d> before = MeanReading(cell, 1.5);
    ASSERT_TRUE(before.has_value()) << "the twin's beacon never reported";

    TwinScene scene;
    TwinLayout layout = ReadTwinLayout((dir / "twin" / "layout.json").string());
    scene.Arrange(layout);
    const Eigen::Vector3d old_place = scene.BeaconPosition();
    const CommandResult moved =
        RunRecon("twin move " + (dir / "twin").string() + " --plate 0.4,-0.25");
    ASSERT_EQ(moved.exit_code, 0) << moved.output;
    layout.plate = {0.4, -0.25};
    scene.Arrange(layout);
    const Eigen::Vector3d new_place = scene.BeaconPosition();
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the twin's next look
    cell.beacons().Poll();                                        // readings from before
    const std::optional<Eigen::Vector3d> after = MeanReading(cell, 1.5);
    ASSERT_TRUE(after.has_value());
    // The hidden frame is rigid: the reading moved as far as the beacon did.
    EXPECT_NEAR((*after - *before).norm(), (new_place - old_place).norm(), 0.03);
  }
  ::kill(twin, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(twin, &status, 0), twin);
  EXPECT_TRUE(WIFEXITED(status)) << "the twin did not stop on SIGTERM";
  EXPECT_EQ(WEXITSTATUS(status), 0);

  // Bad input: a place off the table, not a place, a folder that is not a twin.
  const std::string folder = (dir / "twin").string();
  CommandResult bad = RunRecon("twin move " + folder + " --plate 2,0");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.output, HasSubstr("--plate: (2.000000, 0.000000) is off the table"));
  bad = RunRecon("twin move " + folder + " --bowl abc");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.output, HasSubstr("--bowl \"abc\": expected X,Y in metres"));
  bad = RunRecon("twin move " + (dir / "nothing").string() + " --plate 0.5,0.1");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.output, HasSubstr("is not a twin (no layout.json)"));
  bad = RunRecon("twin move " + folder);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.output, HasSubstr("give --plate, --bowl or --toast"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon::cell
