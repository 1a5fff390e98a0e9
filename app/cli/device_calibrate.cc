#include "app/cli/device_calibrate.h"

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/open_camera.h"
#include "devices/camera/table_tags_file.h"
#include "devices/cell/device_calibration.h"
#include "devices/uwb/beacon_hub.h"
#include "engine/core/error.h"

namespace recon::cli {

calib::CalibrationReport RunDeviceCalibrate(const DeviceCalibrateFlags& flags, int points,
                                            const calib::CalibrationOptions& options) {
  if (flags.camera.empty() || flags.camera_calibration.empty() || flags.table_tags.empty() ||
      flags.beacon_ports.empty()) {
    throw UserError(
        "calibrate with real devices needs --camera, --camera-calibration, --table-tags and "
        "--beacon-port (or --sim for the simulated cell)");
  }
  camera::SilenceOpenCvLogging();
  const camera::CameraCalibration calibration =
      camera::ReadCameraCalibration(flags.camera_calibration);
  const std::vector<camera::TableTag> table_tags = camera::ReadTableTags(flags.table_tags);
  camera::OpenCameraOptions camera_options;
  camera_options.width = calibration.image_width;
  camera_options.height = calibration.image_height;
  camera_options.undistort = calibration;
  const std::unique_ptr<devices::Camera> camera = camera::OpenCamera(flags.camera, camera_options);

  uwb::BeaconHubOptions hub;
  hub.ports = flags.beacon_ports;
  hub.driver.mode = uwb::ParseDwm1001Mode(flags.mode);
  for (const std::string& entry : flags.names) {
    const size_t eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size()) {
      throw UserError("--name '" + entry + "': expected NODE_ID=name, e.g. DECA0000000012AB=plate");
    }
    hub.names[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  uwb::BeaconHub beacons(hub);
  devices::SteadyClock clock;
  std::printf("recon calibrate: %s; %s\n", camera->Describe().c_str(), beacons.Describe().c_str());

  cell::DeviceCalibrationOptions run;
  run.points = points;
  run.calibration = options;
  run.pose.beacon_tag_id = flags.beacon_tag_id;
  run.pose.frames = flags.frames;
  run.pose.max_frames = std::max(flags.frames, 30);
  run.pose.uwb_samples = flags.uwb_samples;
  run.pose.beacon = flags.beacon;
  run.beacon_tag = {flags.beacon_tag_size_m, flags.beacon_tag_height_m};
  const cell::DeviceCalibrationResult result = cell::RunDeviceCalibration(
      *camera, calibration.ToIntrinsics(), table_tags, beacons, clock, run,
      [&](int index, int total) {
        if (index == 0) std::printf("camera pose from the table tags: done\n");
        std::printf("pose %d of %d: put the beacon somewhere new on the table, leave it still%s\n",
                    index + 1, total, flags.no_wait ? "" : ", then press Enter");
        std::fflush(stdout);
        if (flags.no_wait) return;
        std::string line;
        if (!std::getline(std::cin, line)) {
          throw UserError("calibration stopped at pose " + std::to_string(index + 1) +
                          ": standard input closed (nothing was saved)");
        }
      });
  std::printf(
      "camera at (%.3f, %.3f, %.3f) m in the table frame; reprojection %.2f px RMS, "
      "%.2f px max over tags",
      result.camera_pose.camera.position_table_m().x(),
      result.camera_pose.camera.position_table_m().y(),
      result.camera_pose.camera.position_table_m().z(), result.camera_pose.reprojection_rms_px,
      result.camera_pose.reprojection_max_px);
  for (int id : result.camera_pose.used_ids) std::printf(" %d", id);
  std::printf("\n");
  for (size_t i = 0; i < result.poses.size(); ++i) {
    const cell::CollectedPose& p = result.poses[i];
    std::printf(
        "pose %zu: tag (%.3f, %.3f) m in %d/%d frames (spread %.1f mm), UWB (%.3f, %.3f, "
        "%.3f) m from %d samples\n",
        i + 1, p.point.tag_m.x(), p.point.tag_m.y(), p.frames_with_tag, p.frames_tried,
        p.tag_spread_m * 1000, p.point.uwb_m.x(), p.point.uwb_m.y(), p.point.uwb_m.z(),
        p.uwb_samples);
  }
  std::printf("%s\n", result.report.Summary().c_str());
  return result.report;
}

}  // namespace recon::cli
