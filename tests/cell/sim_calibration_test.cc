#include "devices/cell/sim_calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace recon::cell {
namespace {

TEST(SimCalibrationTest, RecoversTheHiddenUwbFrameWithinTheUwbNoise) {
  for (uint64_t seed : {1, 2, 3}) {
    SimCalibrationOptions options;
    options.points = 12;
    options.seed = seed;
    const SimCalibrationResult result = RunSimulatedCalibration(options);
    ASSERT_EQ(result.samples.size(), 12u);
    // The camera's tags are millimetre-accurate ground truth.
    EXPECT_LT(result.tag_rms_error_m, 0.005) << "seed " << seed;
    // One point averages about 10 UWB positions with 7 cm noise per axis: about 2.2 cm per axis,
    // so the fit's residual RMSE is about 3 cm and passes the 10 cm threshold.
    EXPECT_TRUE(result.report.passed) << result.report.Summary();
    EXPECT_LT(result.report.rmse_m, 0.06);
    EXPECT_GT(result.report.rmse_m, 0.005) << "noise must show: the UWB is not perfect";
    // The fitted frame matches the simulator's hidden one within that noise.
    EXPECT_LT(result.offset_error_mean_m, 0.05) << "seed " << seed;
    EXPECT_LT(std::abs(result.yaw_error_rad), 0.15);
    EXPECT_GT(result.uwb_lines, 100);
    EXPECT_THAT(Describe(result), ::testing::ContainsRegex("RMSE [0-9.]+ m"));
  }
}

TEST(SimCalibrationTest, SameSeedSameResultOtherSeedOtherFrame) {
  SimCalibrationOptions options;
  options.points = 6;
  const SimCalibrationResult a = RunSimulatedCalibration(options);
  const SimCalibrationResult b = RunSimulatedCalibration(options);
  EXPECT_EQ(a.report.rmse_m, b.report.rmse_m);
  options.seed = 2;
  const SimCalibrationResult c = RunSimulatedCalibration(options);
  EXPECT_NE(a.hidden_table_to_uwb.translation, c.hidden_table_to_uwb.translation);
}

TEST(SimCalibrationTest, TooFewPointsIsAUserError) {
  SimCalibrationOptions options;
  options.points = 2;
  EXPECT_THROW(RunSimulatedCalibration(options), UserError);
}

}  // namespace
}  // namespace recon::cell
