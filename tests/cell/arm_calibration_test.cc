// The calibration by the arm on an ideal kinematic UR5 (the joints integrate what they are
// told): it visits every planned place, takes the beacon's readings there and recovers a hidden
// UWB frame; a place the arm cannot reach is skipped and said; the e-stop pauses it; a silent
// beacon is said and nothing is taken meanwhile.

#include "devices/cell/arm_calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::cell {
namespace {

using ::testing::HasSubstr;

constexpr double kPeriod_s = 0.1;

calib::RigidTransform HiddenFrame() {
  return {Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).matrix(),
          Eigen::Vector3d(1.5, -2.0, 0.4)};
}

/// Runs the calibration against an ideal arm and a beacon with 1 cm of noise (seed 17), up to
/// `max_s` of clock. `stuck` freezes the arm while the calibration heads for that place (index).
struct ArmRun {
  explicit ArmRun(ArmCalibrationOptions options) : calibration(std::move(options), {}) {}

  void Go(double max_s, int stuck = -1, double held_from_s = -1, double held_to_s = -1,
          double silent_from_s = -1, double silent_to_s = -1) {
    Rng rng(17);
    while (!calibration.Done() && now_s < max_s) {
      std::vector<devices::BeaconSample> samples;
      const bool silent = now_s >= silent_from_s && now_s < silent_to_s;
      if (!silent) {
        devices::BeaconSample s;
        s.beacon = "plate";
        const Eigen::Vector3d noise(rng.Normal(), rng.Normal(), rng.Normal());
        s.position_uwb_m = HiddenFrame().Apply(calibration.BeaconAt(q) + 0.01 * noise);
        samples.push_back(s);
      }
      const bool held = now_s >= held_from_s && now_s < held_to_s;
      const int place = calibration.status().taken + calibration.skipped();
      const std::array<double, 6> v = calibration.Update(q, samples, now_s, kPeriod_s, held);
      if (held) {
        for (double x : v) EXPECT_EQ(x, 0.0) << "the arm is held";
      }
      if (place != stuck) {
        for (int i = 0; i < 6; ++i) q[i] += v[i] * kPeriod_s;
      }
      if (silent && calibration.status().beacon_silent)
        saw_silence_prompt = calibration.status().prompt;
      if (held) saw_held_prompt = calibration.status().prompt;
      now_s += kPeriod_s;
    }
  }

  ArmCalibration calibration;
  std::array<double, 6> q = worlds::Ur5Arm::kHome;
  double now_s = 0;
  std::string saw_silence_prompt, saw_held_prompt;
};

TEST(ArmCalibrationTest, TheArmCarriesTheBeaconToEveryPlaceAndTheFitFindsTheHiddenFrame) {
  ArmCalibrationOptions options;
  options.points = 6;
  options.beacon = "plate";
  options.beacon_offset_m = {0.0, 0.0, 0.03};
  ArmRun run(options);
  ASSERT_EQ(run.calibration.plan().size(), 6u);
  // The places spread over the table at two heights (not all in one plane).
  EXPECT_NE(run.calibration.plan()[0].z(), run.calibration.plan()[1].z());
  run.Go(300);
  ASSERT_TRUE(run.calibration.Done()) << run.calibration.status().prompt;
  EXPECT_EQ(run.calibration.poses().size(), 6u);
  EXPECT_EQ(run.calibration.skipped(), 0);
  EXPECT_THAT(run.calibration.status().prompt, HasSubstr("All 6 places done: 6 taken"));
  for (size_t i = 0; i < 6; ++i) {
    // Each place's truth is where the beacon was carried to.
    EXPECT_LT((run.calibration.poses()[i].point.tag_m - run.calibration.plan()[i]).norm(), 0.006)
        << i;
    EXPECT_GE(run.calibration.poses()[i].uwb_samples, options.min_uwb_samples);
  }
  const calib::CalibrationReport report = run.calibration.Fit();
  EXPECT_TRUE(report.passed) << report.Summary();
  // The fit maps each place's UWB position back onto the place.
  for (const Eigen::Vector3d& p : run.calibration.plan()) {
    EXPECT_LT((report.transform.Apply(HiddenFrame().Apply(p)) - p).norm(), 0.02) << p.transpose();
  }
}

TEST(ArmCalibrationTest, APlaceOutOfReachIsSkippedAndSaidAndTheRestAreTaken) {
  ArmCalibrationOptions options;
  options.points = 5;
  options.speed_m_s = 0.3;
  options.move_timeout_s = 8;
  ArmRun run(options);
  run.Go(300, /*stuck=*/2);
  ASSERT_TRUE(run.calibration.Done());
  EXPECT_EQ(run.calibration.skipped(), 1);
  EXPECT_EQ(run.calibration.poses().size(), 4u);
  EXPECT_THAT(run.calibration.status().prompt, HasSubstr("4 taken, 1 skipped"));
  EXPECT_TRUE(run.calibration.Fit().passed);
}

TEST(ArmCalibrationTest, TheEStopPausesItAndASilentBeaconIsSaidWithNothingTaken) {
  ArmCalibrationOptions options;
  options.points = 4;
  options.speed_m_s = 0.3;
  options.move_timeout_s = 8;
  ArmRun run(options);
  // Held for 30 s early on: far past the 8 s move timeout, yet nothing is skipped. Silent later for
  // 4 s: said, and no place is taken from readings that did not come.
  run.Go(300, -1, 1.0, 31.0, 40.0, 44.0);
  ASSERT_TRUE(run.calibration.Done());
  EXPECT_EQ(run.calibration.skipped(), 0);
  EXPECT_EQ(run.calibration.poses().size(), 4u);
  EXPECT_THAT(run.saw_held_prompt, HasSubstr("the e-stop holds the arm"));
  EXPECT_THAT(run.saw_silence_prompt, HasSubstr("No reading from the beacon on the arm"));
}

TEST(ArmCalibrationTest, TooFewPlacesOrBadOptionsAreRefusedByName) {
  ArmCalibrationOptions options;
  options.points = 3;
  options.speed_m_s = 0.3;
  options.move_timeout_s = 8;
  ArmRun run(options);
  run.Go(60, /*stuck=*/0);  // the first place is never reached: 2 of 3 taken
  EXPECT_THAT([&] { run.calibration.Fit(); },
              ::testing::ThrowsMessage<UserError>(HasSubstr("reached only 2 of 3")));
  ArmCalibrationOptions bad;
  bad.points = 2;
  EXPECT_THROW(ArmCalibration(bad, {}), UserError);
  bad = {};
  bad.speed_m_s = 0;
  EXPECT_THROW(ArmCalibration(bad, {}), UserError);
  bad = {};
  bad.max_xy = bad.min_xy;
  EXPECT_THROW(ArmCalibration(bad, {}), UserError);
}

}  // namespace
}  // namespace recon::cell
