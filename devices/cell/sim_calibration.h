#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/calib/calibration.h"

namespace recon::cell {

/// How the simulated cell's calibration run is set up.
struct SimCalibrationOptions {
  int points = 12;             ///< static beacon poses to collect
  int updates_per_point = 10;  ///< 1 s of 10 Hz UWB lines averaged per pose
  uint64_t seed = 1;           ///< beacon poses, UWB noise and the hidden UWB frame
  calib::CalibrationOptions calibration;
  int camera_width = 640;  ///< the tags need a detailed frame; the policy's 64 x 64 would not do
  int camera_height = 480;
};

/// One collected pose, with what each side saw.
struct SimCalibrationSample {
  Eigen::Vector3d true_table_m;   ///< where the beacon really is (the simulator's truth)
  calib::CalibrationPoint point;  ///< the camera's tag position and the averaged UWB position
  int uwb_readings = 0;           ///< lines that parsed into a position during this pose
};

/// The outcome: the fit, plus how well it recovered the simulator's hidden UWB frame.
struct SimCalibrationResult {
  calib::CalibrationReport report;
  std::vector<SimCalibrationSample> samples;
  calib::RigidTransform hidden_table_to_uwb;
  /// Over the table area: |fitted(hidden(p)) - p|, the error the fitted transform leaves on
  /// live readings once UWB noise is averaged away (metres), mean and max over a grid.
  double offset_error_mean_m = 0;
  double offset_error_max_m = 0;
  double yaw_error_rad = 0;
  /// Tag detection vs the simulator's truth, over the collected poses (metres, RMS).
  double tag_rms_error_m = 0;
  int64_t uwb_lines = 0, uwb_malformed = 0, uwb_dropped = 0, uwb_garbled = 0;
  /// Places (table x, y) where the camera could not see the beacon's tag, so the beacon was put
  /// somewhere else, as a teacher would move it (in the order they happened).
  std::vector<Eigen::Vector2d> replaced_unseen;
};

/// How many places a calibration point is tried at before the calibration gives up on it.
constexpr int kPlacementsPerPoint = 20;

using CalibrationProgress = std::function<void(int done, int total)>;

/// Runs a calibration in the simulated tabletop cell as a teacher would: the beacon (on the
/// plate) is put at `points` places; at each the top-down camera's AprilTag gives its table
/// position and one second of DWM1001 `lec` lines, printed by SimulatedDwm1001 with its hidden
/// table-to-UWB pose and parsed by LecLineParser, gives its UWB position; then the rigid fit.
/// A place where the camera does not see the tag (occluded, out of view) is not fatal: the
/// beacon goes to another random place and the skipped one is listed in replaced_unseen.
/// Throws UserError when the tag is not seen at kPlacementsPerPoint places for one point, the
/// UWB gives no position, or the renderer cannot be made.
SimCalibrationResult RunSimulatedCalibration(const SimCalibrationOptions& options,
                                             const CalibrationProgress& progress = {});

/// A multi-line text for the CLI: Summary() of the report (with its "RMSE <v> m" line), and the
/// hidden-offset comparison.
std::string Describe(const SimCalibrationResult& result);

}  // namespace recon::cell
