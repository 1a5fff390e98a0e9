#pragma once

#include <functional>
#include <string>
#include <vector>

#include "devices/camera/camera_pose.h"
#include "devices/camera/table_tags_file.h"
#include "devices/cell/calibration_collector.h"
#include "engine/calib/calibration.h"

namespace recon::cell {

/// How a calibration with real devices is run.
struct DeviceCalibrationOptions {
  int points = 8;  ///< static beacon poses
  PoseCollectOptions pose;
  /// The tag on the beacon: its black border's size, and its face's height over the table.
  tags::TagSpec beacon_tag{0.0352, 0.06};
  calib::CalibrationOptions calibration;
};

/// The fit, and everything it rests on.
struct DeviceCalibrationResult {
  camera::CameraPoseEstimate camera_pose;  ///< where the camera is, from the table tags
  std::vector<CollectedPose> poses;
  calib::CalibrationReport report;
};

/// Called before pose `index` (0-based) of `total`: the teacher moves the beacon to a new place
/// on the table, leaves it still, and confirms (the CLI waits for Enter).
using WaitForPose = std::function<void(int index, int total)>;

/// The simulated cell's calibration flow with real devices: the camera's pose in the table
/// frame is estimated from the table tags in the first frame (EstimateCameraPose), then at each
/// of `points` poses CollectPose pairs the beacon tag's table position with the beacon's
/// averaged UWB position, and the rigid fit with its residual statistics closes it (Calibrate).
/// The camera must deliver undistorted frames described by `intrinsics`. Throws UserError naming
/// what is missing: too few table tags, a pose whose tag or beacon was not seen, a degenerate
/// set of poses.
DeviceCalibrationResult RunDeviceCalibration(devices::Camera& camera,
                                             const tags::CameraIntrinsics& intrinsics,
                                             const std::vector<camera::TableTag>& table_tags,
                                             devices::BeaconSource& beacons,
                                             const devices::Clock& clock,
                                             const DeviceCalibrationOptions& options,
                                             const WaitForPose& wait_for_pose);

}  // namespace recon::cell
