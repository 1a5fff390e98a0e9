#include "devices/cell/device_calibration.h"

#include "engine/core/error.h"

namespace recon::cell {

DeviceCalibrationResult RunDeviceCalibration(devices::Camera& camera,
                                             const tags::CameraIntrinsics& intrinsics,
                                             const std::vector<camera::TableTag>& table_tags,
                                             devices::BeaconSource& beacons,
                                             const devices::Clock& clock,
                                             const DeviceCalibrationOptions& options,
                                             const WaitForPose& wait_for_pose) {
  if (options.points < 3) throw UserError("calibration needs at least 3 beacon poses");
  for (const camera::TableTag& tag : table_tags) {
    if (tag.id == options.pose.beacon_tag_id) {
      throw UserError("tag " + std::to_string(tag.id) +
                      " is both a table tag and the beacon's tag; give the beacon another id");
    }
  }
  DeviceCalibrationResult result;
  tags::TagDetector detector;
  {
    const devices::CameraFrame first = camera.Capture();
    result.camera_pose =
        camera::EstimateCameraPose(intrinsics, table_tags, detector.Detect(first.image));
  }
  tags::TableLocator locator(result.camera_pose.camera, options.beacon_tag);
  std::vector<calib::CalibrationPoint> points;
  for (int i = 0; i < options.points; ++i) {
    if (wait_for_pose) wait_for_pose(i, options.points);
    result.poses.push_back(CollectPose(camera, beacons, locator, clock, options.pose,
                                       "calibration pose " + std::to_string(i + 1)));
    points.push_back(result.poses.back().point);
  }
  result.report = calib::Calibrate(points, options.calibration);
  return result;
}

}  // namespace recon::cell
