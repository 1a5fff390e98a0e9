#include "devices/uwb/simulated_dwm1001.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "devices/uwb/lec_parser.h"
#include "engine/calib/calibration.h"

namespace recon::uwb {
namespace {

SimulatedDwm1001Options HiddenOffset(uint64_t seed) {
  SimulatedDwm1001Options options;
  options.table_to_uwb.rotation =
      Eigen::AngleAxisd(-0.25, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  options.table_to_uwb.translation = {1.1, 0.7, 0.05};
  options.seed = seed;
  return options;
}

TEST(SimulatedDwm1001Test, SameSeedSameBytes) {
  SimulatedDwm1001 a(HiddenOffset(4)), b(HiddenOffset(4)), c(HiddenOffset(5));
  bool any_difference = false;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d p(0.01 * i, 0.2, 0.0);
    const std::string line = a.NextUpdate(p);
    EXPECT_EQ(line, b.NextUpdate(p));
    any_difference |= line != c.NextUpdate(p);
  }
  EXPECT_TRUE(any_difference);
}

TEST(SimulatedDwm1001Test, NoiseDropsAndGarblingAreWhatWasConfigured) {
  SimulatedDwm1001Options options = HiddenOffset(6);
  SimulatedDwm1001 beacon(options);
  LecLineParser parser;
  std::vector<UwbReading> readings;
  constexpr int kUpdates = 4000;
  const Eigen::Vector3d table(0.3, -0.2, 0.0);
  for (int i = 0; i < kUpdates; ++i) parser.Feed(beacon.NextUpdate(table), readings);

  // Drops and garbling near their rates (2% and 3% of 4000: 80 and 120, binomial s.d. ~9 and ~11).
  EXPECT_NEAR(beacon.dropped(), 80, 40);
  EXPECT_NEAR(beacon.garbled(), 120, 45);
  // Every update that was not dropped printed one line, and the parser accounted for each.
  EXPECT_EQ(parser.stats().lines, kUpdates - beacon.dropped());
  EXPECT_GT(parser.stats().resynced, 20);   // the echo fragments were recovered
  EXPECT_GT(parser.stats().malformed, 20);  // the cut lines were refused

  // Readings with a position scatter about the true UWB position with the configured noise.
  const Eigen::Vector3d truth = options.table_to_uwb.Apply(table);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  int n = 0;
  for (const UwbReading& r : readings) {
    if (!r.has_position) continue;
    const Eigen::Vector3d d = Eigen::Vector3d(r.x_m, r.y_m, r.z_m) - truth;
    sum += d;
    sum_sq += d.cwiseProduct(d);
    ++n;
  }
  ASSERT_GT(n, 3500);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(sum[k] / n, 0.0, 0.01);
    // 2-decimal printing adds about 0.3 cm of rounding to the 7 cm noise.
    EXPECT_NEAR(std::sqrt(sum_sq[k] / n), options.position_noise_m, 0.006);
  }
}

// The simulated cell's calibration path without the camera: beacons print real lines, the
// parser reads them, averaged readings are paired with known table positions, and the fit must
// recover the hidden offset within what the UWB noise allows.
TEST(SimulatedDwm1001Test, CalibrationRecoversTheHiddenOffsetThroughRealLines) {
  const SimulatedDwm1001Options options = HiddenOffset(7);
  SimulatedDwm1001 beacon(options);
  LecLineParser parser;
  std::vector<calib::CalibrationPoint> points;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector3d table(-0.4 + 0.2 * i, -0.3 + 0.2 * j, 0.0);
      std::vector<UwbReading> readings;
      for (int k = 0; k < 10; ++k) parser.Feed(beacon.NextUpdate(table), readings);  // 1 s
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      int n = 0;
      for (const UwbReading& r : readings) {
        if (!r.has_position) continue;
        mean += Eigen::Vector3d(r.x_m, r.y_m, r.z_m);
        ++n;
      }
      ASSERT_GT(n, 5);
      points.push_back({table, mean / n});
    }
  }
  const calib::CalibrationReport report = calib::Calibrate(points);
  // Expected: UWB -> table is the inverse of the hidden table -> UWB pose.
  const Eigen::Matrix3d r_inv = options.table_to_uwb.rotation.transpose();
  const Eigen::Vector3d t_inv = -r_inv * options.table_to_uwb.translation;
  // 20 points of 1 s averages (noise ~7 / sqrt(10) ~ 2.2 cm per axis): offset within 3 cm.
  EXPECT_LT((report.transform.translation.head<2>() - t_inv.head<2>()).norm(), 0.03);
  EXPECT_NEAR(report.transform.YawRad(), 0.25, 0.05);
  EXPECT_TRUE(report.passed) << report.Summary();
  EXPECT_LT(report.rmse_m, 0.06);
}

}  // namespace
}  // namespace recon::uwb
