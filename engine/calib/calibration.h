#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/calib/rigid_fit.h"

namespace recon::calib {

/// One static pose of a beacon: where the camera's AprilTag puts it in the table frame (ground
/// truth), and where the UWB system puts it in its own anchor frame.
struct CalibrationPoint {
  Eigen::Vector3d tag_m;
  Eigen::Vector3d uwb_m;
};

struct CalibrationOptions {
  FitDimension dimension = FitDimension::k2D;
  /// The fit passes when the RMSE of the inlier residuals is at most this.
  double pass_rmse_m = 0.10;
  /// A point is an outlier when its residual exceeds both the pass threshold and the median
  /// residual plus this many robust standard deviations (1.4826 x median absolute deviation).
  double outlier_sigmas = 3.0;
  /// At most this fraction of the points may be outliers for the fit to pass.
  double max_outlier_fraction = 0.2;
};

/// The fitted UWB -> table transform and how well it explains the points.
///
/// Residuals are aligned UWB position minus tag position, over the fitted axes (x, y in 2-D).
/// Statistics are over the inliers; the outliers are flagged and left out of the final fit.
struct CalibrationReport {
  RigidTransform transform;
  CalibrationOptions options;
  std::vector<CalibrationPoint> points;
  std::vector<Eigen::Vector3d> residual_m;  ///< per point (z is 0 in 2-D)
  std::vector<double> residual_norm_m;      ///< per point
  std::vector<bool> outlier;                ///< per point
  int num_inliers = 0;
  double rmse_m = 0, mean_m = 0, median_m = 0, p95_m = 0;
  Eigen::Vector3d bias_m = Eigen::Vector3d::Zero();  ///< mean residual per axis (inliers)
  bool passed = false;

  /// A one-paragraph summary for the CLI: the fit, "RMSE <v> m", the statistics, pass/fail.
  std::string Summary() const;
};

/// Fits the transform, flags outliers, refits on the inliers and computes the statistics.
/// Throws UserError for too few, non-finite or degenerate points (see FitRigid).
CalibrationReport Calibrate(const std::vector<CalibrationPoint>& points,
                            const CalibrationOptions& options = {});

/// Maps a live UWB reading into the table frame.
inline Eigen::Vector3d ToTableFrame(const CalibrationReport& report, const Eigen::Vector3d& uwb_m) {
  return report.transform.Apply(uwb_m);
}

/// Writes the report as versioned JSON, atomically. UserError if the file cannot be written.
void SaveCalibration(const CalibrationReport& report, const std::string& path);
/// Reads a saved calibration; UserError naming the file and the field that is missing or wrong,
/// or a version newer than this program understands.
CalibrationReport LoadCalibration(const std::string& path);

}  // namespace recon::calib
