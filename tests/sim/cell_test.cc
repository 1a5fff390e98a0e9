// The simulated cell driven through the device interfaces only, as the recorder will drive it:
// the scripted teacher's commands go to the arm, the camera and beacons are read every step.

#include "devices/sim/simulated_cell.h"

#include <gtest/gtest.h>

#include <cmath>

#include "devices/sim/hidden_uwb_frame.h"
#include "devices/sim/scripted_teleop.h"
#include "engine/calib/calibration.h"
#include "engine/core/error.h"
#include "engine/worlds/dynamic2d.h"
#include "tests/sim/sim_test_support.h"

namespace recon::sim {
namespace {

TEST(SimulatedCellTest, ScriptedDemonstrationThroughTheInterfacesPutsTheToastOnThePlate) {
  auto cell = testing::MakeCell(1);  // installation seed 1
  ScriptedTeleop scripted(cell->world());
  devices::Teleop& teleop = scripted;
  devices::Camera& camera = cell->camera();
  devices::BeaconSource& beacons = cell->beacons();
  devices::Arm& arm = cell->arm();
  const calib::RigidTransform uwb_to_table = Inverse(cell->hidden_table_to_uwb());
  EXPECT_EQ(teleop.Describe(), "scripted expert of tabletop");

  for (uint64_t seed : {100, 101}) {  // scenario seeds; 101 puts the plate on the other side
    cell->Reset(seed);
    scripted.Restart();
    EXPECT_FALSE(cell->world().TaskSucceeded());
    const double start_s = cell->clock().NowSeconds();
    int steps = 0, samples = 0;
    int closed_steps = 0;
    while (true) {
      const devices::TeleopCommand command = teleop.Poll();
      if (command.finished) break;
      cell->Step(command);
      ++steps;
      closed_steps += command.close_gripper ? 1 : 0;
      const devices::JointState state = arm.State();
      EXPECT_NEAR(state.timestamp_s, start_s + 0.1 * steps, 1e-9);
      EXPECT_EQ(camera.Capture().image.width, 64);
      for (const devices::BeaconSample& s : beacons.Poll()) {
        ++samples;
        const Eigen::Vector3d truth = cell->world().BeaconPosition();
        EXPECT_LT((uwb_to_table.Apply(s.position_uwb_m) - truth).head<2>().norm(), 0.3);
      }
      ASSERT_LT(steps, 1000) << "the teleop never finished";
    }
    EXPECT_EQ(steps, worlds::Tabletop::kEpisodeLength) << "seed " << seed;
    EXPECT_TRUE(cell->world().TaskSucceeded())
        << "seed " << seed << ": toast " << cell->world().ToastPosition().transpose();
    EXPECT_LT(cell->world().EpisodeMetric(), worlds::Tabletop::kPlateRadius_m);
    // The teacher carried the toast with the gripper closed and let go over the plate.
    EXPECT_GT(closed_steps, 10);
    EXPECT_LT(closed_steps, steps);
    EXPECT_FALSE(cell->world().arm().GripperClosed());
    // One update per 0.1 s step at 10 Hz, less drops and cut lines (about 3.5%).
    EXPECT_GE(samples, steps * 92 / 100);
    EXPECT_LE(samples, steps);
    EXPECT_TRUE(teleop.Poll().finished) << "finished stays finished until Restart";
  }
  const devices::BeaconSourceStats stats = beacons.Stats();
  EXPECT_EQ(stats.readings + stats.malformed, stats.lines);
  EXPECT_GT(stats.malformed, 0) << "400 updates at 1.5% cut lines";
}

// Calibration from the cell's own streams: the plate (and its beacon) moves with each scenario;
// one second of samples per scenario is averaged and paired with the beacon's true position.
TEST(SimulatedCellTest, CollectedBeaconSamplesCalibrateToTheHiddenFrame) {
  for (uint64_t installation : {1, 2}) {
    auto cell = testing::MakeCell(installation);
    std::vector<calib::CalibrationPoint> points;
    for (uint64_t seed = 200; seed < 208; ++seed) {  // scenario seeds 200-207
      cell->Reset(seed);
      cell->beacons().Poll();  // drop what was printed while the plate was elsewhere
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int n = 0;
      for (int step = 0; step < 10; ++step) {
        cell->Step(devices::TeleopCommand{});
        for (const auto& s : cell->beacons().Poll()) {
          sum += s.position_uwb_m;
          ++n;
        }
      }
      ASSERT_GT(n, 5);
      points.push_back({cell->world().BeaconPosition(), sum / n});
    }
    const calib::CalibrationReport report = calib::Calibrate(points);
    EXPECT_TRUE(report.passed) << report.Summary();
    // The fit agrees with the hidden frame's inverse over the table, within the averaged noise.
    const calib::RigidTransform truth = Inverse(cell->hidden_table_to_uwb());
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(0.3, -0.35, 0.02), Eigen::Vector3d(0.7, 0.35, 0.02)}) {
      const Eigen::Vector3d uwb = cell->hidden_table_to_uwb().Apply(p);
      EXPECT_LT((report.transform.Apply(uwb) - truth.Apply(uwb)).head<2>().norm(), 0.06)
          << "installation " << installation;
    }
  }
}

TEST(SimulatedCellTest, SameSeedsSameStreams) {
  auto a = testing::MakeCell(3);
  auto b = testing::MakeCell(3);
  EXPECT_EQ(a->hidden_table_to_uwb().translation, b->hidden_table_to_uwb().translation);
  EXPECT_NE(a->hidden_table_to_uwb().translation,
            testing::MakeCell(4)->hidden_table_to_uwb().translation);
  a->Reset(5);
  b->Reset(5);
  ScriptedTeleop ta(a->world()), tb(b->world());
  for (int step = 0; step < 20; ++step) {
    a->Step(ta.Poll());
    b->Step(tb.Poll());
    const auto sa = a->beacons().Poll(), sb = b->beacons().Poll();
    ASSERT_EQ(sa.size(), sb.size());
    for (size_t i = 0; i < sa.size(); ++i) EXPECT_EQ(sa[i].position_uwb_m, sb[i].position_uwb_m);
    ASSERT_EQ(a->camera().Capture().image.rgb, b->camera().Capture().image.rgb) << "step " << step;
    ASSERT_EQ(a->arm().State().position_rad, b->arm().State().position_rad);
  }
}

TEST(SimulatedCellTest, ScriptedTeleopNeedsAnArmWorld) {
  worlds::Dynamic2D world{worlds::Dynamic2DOptions{}};
  ScriptedTeleop teleop(world);
  EXPECT_THROW(teleop.Poll(), UserError);
  EXPECT_THROW(SimulatedCell(SimulatedCellOptions{}, nullptr), UserError);
}

}  // namespace
}  // namespace recon::sim
