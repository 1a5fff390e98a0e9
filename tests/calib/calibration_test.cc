#include "engine/calib/calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::calib {
namespace {

using ::testing::HasSubstr;

// A simulated session: the UWB frame is the table frame moved by a hidden offset, plus noise.
struct Scenario {
  RigidTransform uwb_to_table;
  std::vector<CalibrationPoint> points;
};

Scenario MakeScenario(uint64_t seed, int n, double noise_m) {
  Rng rng(seed);
  Scenario s;
  s.uwb_to_table.rotation = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  s.uwb_to_table.translation = {0.8, -0.3, 0.0};
  const RigidTransform table_to_uwb{
      s.uwb_to_table.rotation.transpose(),
      -s.uwb_to_table.rotation.transpose() * s.uwb_to_table.translation};
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d tag(rng.Uniform(-0.5, 0.5), rng.Uniform(-0.4, 0.4), 0.0);
    const Eigen::Vector3d noise(noise_m * rng.Normal(), noise_m * rng.Normal(), 0.0);
    s.points.push_back({tag, table_to_uwb.Apply(tag) + noise});
  }
  return s;
}

TEST(CalibrationTest, RecoversTheHiddenOffsetWithinTheNoise) {
  const Scenario s = MakeScenario(11, 60, 0.05);
  const CalibrationReport r = Calibrate(s.points);
  // With 60 points of 5 cm noise the offset is known to about 5 / sqrt(60) ~ 0.7 cm.
  EXPECT_LT((r.transform.translation - s.uwb_to_table.translation).norm(), 0.03);
  EXPECT_NEAR(r.transform.YawRad(), 0.4, 0.05);
  // Residual RMS of 2-D Gaussian noise with sigma 5 cm is about 5 * sqrt(2) cm.
  EXPECT_NEAR(r.rmse_m, 0.05 * std::sqrt(2.0), 0.02);
  EXPECT_TRUE(r.passed);
  EXPECT_LT(r.bias_m.norm(), 1e-9);  // least squares leaves no mean residual on the inliers
  EXPECT_LE(r.median_m, r.p95_m);
  EXPECT_THAT(r.Summary(), HasSubstr("RMSE "));
  EXPECT_THAT(r.Summary(), HasSubstr("PASS"));
}

TEST(CalibrationTest, StatisticsMatchTheirDefinitions) {
  // Hand-made residuals: identity frames, tag points offset by known amounts.
  std::vector<CalibrationPoint> points;
  const double offsets[] = {0.01, -0.02, 0.03, -0.04, 0.05, -0.03};
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d p(i % 3, i / 3, 0);
    points.push_back({p, p});
  }
  CalibrationOptions options;
  options.outlier_sigmas = 100;  // no outliers in this test
  CalibrationReport r = Calibrate(points, options);
  EXPECT_NEAR(r.rmse_m, 0.0, 1e-12);
  for (int i = 0; i < 6; ++i) points[i].uwb_m.z() += offsets[i];  // z is not fitted in 2-D
  r = Calibrate(points, options);
  EXPECT_NEAR(r.rmse_m, 0.0, 1e-12);
  EXPECT_NEAR(r.transform.translation.z(), -(0.01 - 0.02 + 0.03 - 0.04 + 0.05 - 0.03) / 6, 1e-12);

  // Residual norms are computed over the inliers and match the textbook formulas.
  const Scenario s = MakeScenario(3, 21, 0.04);
  r = Calibrate(s.points, options);
  std::vector<double> norms = r.residual_norm_m;
  double sum = 0, sum_sq = 0;
  for (double e : norms) {
    sum += e;
    sum_sq += e * e;
  }
  std::sort(norms.begin(), norms.end());
  EXPECT_NEAR(r.mean_m, sum / 21, 1e-12);
  EXPECT_NEAR(r.rmse_m, std::sqrt(sum_sq / 21), 1e-12);
  EXPECT_NEAR(r.median_m, norms[10], 1e-12);
  EXPECT_NEAR(r.p95_m, norms[19], 1e-12);  // nearest rank: ceil(0.95 * 21) = 20th value
}

TEST(CalibrationTest, AnOutlierIsFlaggedAndDoesNotDragTheFit) {
  Scenario s = MakeScenario(5, 30, 0.02);
  s.points[7].uwb_m += Eigen::Vector3d(0.8, -0.5, 0);  // the beacon moved during this reading
  const CalibrationReport r = Calibrate(s.points);
  ASSERT_TRUE(r.outlier[7]);
  EXPECT_EQ(r.num_inliers, 29);
  for (size_t i = 0; i < r.outlier.size(); ++i) {
    if (i != 7) {
      EXPECT_FALSE(r.outlier[i]) << i;
    }
  }
  EXPECT_LT((r.transform.translation - s.uwb_to_table.translation).norm(), 0.02);
  EXPECT_TRUE(r.passed);
}

TEST(CalibrationTest, NoisyBeaconsFailTheThreshold) {
  const Scenario s = MakeScenario(6, 40, 0.2);
  const CalibrationReport r = Calibrate(s.points);
  EXPECT_FALSE(r.passed);
  EXPECT_GT(r.rmse_m, 0.1);
  EXPECT_THAT(r.Summary(), HasSubstr("FAIL"));
}

TEST(CalibrationTest, SaveLoadRoundTripAndBadFiles) {
  const Scenario s = MakeScenario(8, 12, 0.03);
  const CalibrationReport r = Calibrate(s.points);
  const std::string dir = ::testing::TempDir() + "/calibration";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/calibration.json";
  SaveCalibration(r, path);
  const CalibrationReport loaded = LoadCalibration(path);
  EXPECT_LT((loaded.transform.translation - r.transform.translation).norm(), 1e-9);
  EXPECT_NEAR(loaded.rmse_m, r.rmse_m, 1e-9);
  const Eigen::Vector3d live(0.1, 0.2, 0.0);
  EXPECT_LT((ToTableFrame(loaded, live) - ToTableFrame(r, live)).norm(), 1e-9);

  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  auto write = [&](const nlohmann::json& content) {
    const std::string bad = dir + "/bad.json";
    std::ofstream(bad) << content.dump();
    return bad;
  };
  auto error_of = [](const std::string& file) {
    try {
      LoadCalibration(file);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  nlohmann::json missing = j;
  missing["options"].erase("pass_rmse_m");
  EXPECT_THAT(error_of(write(missing)), HasSubstr("pass_rmse_m"));
  nlohmann::json newer = j;
  newer["version"] = 99;
  EXPECT_THAT(error_of(write(newer)), HasSubstr("newer"));
  nlohmann::json edited = j;
  edited["transform"]["translation_m"][0] = 5.0;
  EXPECT_THAT(error_of(write(edited)), HasSubstr("does not match"));
  nlohmann::json short_vec = j;
  short_vec["points"][3]["uwb_m"] = {1.0, 2.0};
  EXPECT_THAT(error_of(write(short_vec)), HasSubstr("points[3].uwb_m"));
  const std::string truncated = dir + "/truncated.json";
  std::ofstream(truncated) << j.dump().substr(0, 40);
  EXPECT_THAT(error_of(truncated), HasSubstr("not valid JSON"));
  EXPECT_THAT(error_of(dir + "/missing.json"), HasSubstr("cannot read"));
  // The good file was never touched by the failures above.
  EXPECT_LT((LoadCalibration(path).transform.translation - r.transform.translation).norm(), 1e-9);
}

}  // namespace
}  // namespace recon::calib
